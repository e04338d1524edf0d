/**
 * OIDN's input and output processing for HDR colour (core/color.h,
 * core/autoexposure): the image is scaled so its log-average luminance is
 * 0.18 (autoexposure), mapped through the perceptually uniform (PU) transfer
 * function and normalized so 65504 maps to 1; the network's output goes
 * back through the inverse. Albedo is clamped to [0, 1]; normals are clamped
 * to [-1, 1] and mapped to [0, 1].
 */

// PU curve fitted by OIDN (Aydin et al. 2008, "Extending quality metrics to full luminance range images").
const A = 1.41283765e3;
const B = 1.64593172;
const C = 0.431384981;
const D = -2.94139609e-3;
const E = 0.192653254;
const F = 6.26026094e-3;
const G = 0.998620152;
const Y0 = 1.57945760e-6;
const Y1 = 3.22087631e-2;
const X0 = 2.23151711e-3;
const X1 = 3.70974749e-1;
const HDR_Y_MAX = 65504;

export function puForward(y: number): number {
  if (y <= Y0) return A * y;
  if (y <= Y1) return B * Math.pow(y, C) + D;
  return E * Math.log(y + F) + G;
}

export function puInverse(x: number): number {
  if (x <= X0) return x / A;
  if (x <= X1) return Math.pow((x - D) / B, 1 / C);
  return Math.exp((x - G) / E) - F;
}

const NORM_SCALE = 1 / puForward(HDR_Y_MAX);

/** Colour value -> network input (after the exposure scale). */
export function colorForward(value: number, inputScale: number): number {
  const y = Number.isFinite(value) ? Math.min(Math.max(value * inputScale, 0), HDR_Y_MAX) : 0;
  return puForward(y) * NORM_SCALE;
}

/** Network output -> colour value. */
export function colorInverse(x: number, inputScale: number): number {
  const clean = Number.isFinite(x) ? Math.max(x, 0) : 0;
  return Math.max(puInverse(clean / NORM_SCALE), 0) / inputScale;
}

/**
 * OIDN's autoexposure: mean luminance of bins of at most 16x16 pixels, the
 * exponential of the mean log2 of the bins brighter than 1e-8, scaled to
 * key 0.18. Returns 1 for a black image.
 */
export function autoexposure(rgba: Float32Array, width: number, height: number, stride = 4): number {
  const bin = 16;
  const binsX = Math.ceil(width / bin);
  const binsY = Math.ceil(height / bin);
  let sum = 0;
  let count = 0;
  for (let by = 0; by < binsY; by++) {
    for (let bx = 0; bx < binsX; bx++) {
      const x0 = Math.floor((bx * width) / binsX);
      const x1 = Math.floor(((bx + 1) * width) / binsX);
      const y0 = Math.floor((by * height) / binsY);
      const y1 = Math.floor(((by + 1) * height) / binsY);
      let luminance = 0;
      for (let y = y0; y < y1; y++) {
        for (let x = x0; x < x1; x++) {
          const i = (y * width + x) * stride;
          const l = 0.212671 * rgba[i] + 0.71516 * rgba[i + 1] + 0.072169 * rgba[i + 2];
          if (Number.isFinite(l)) luminance += l;
        }
      }
      luminance /= Math.max(1, (x1 - x0) * (y1 - y0));
      if (luminance > 1e-8) {
        sum += Math.log2(luminance);
        count++;
      }
    }
  }
  return count > 0 ? 0.18 / Math.pow(2, sum / count) : 1;
}

export function albedoInput(value: number): number {
  return Number.isFinite(value) ? Math.min(Math.max(value, 0), 1) : 0;
}

export function normalInput(value: number): number {
  return Number.isFinite(value) ? Math.min(Math.max(value, -1), 1) * 0.5 + 0.5 : 0.5;
}
