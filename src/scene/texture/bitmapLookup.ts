/**
 * The reference texture lookup of the scene format ("Textures"): exactly
 * Mitsuba's `bitmap` texture (bilinear, repeat, no mipmaps), in double
 * precision. The GLSL lookup is tested against the same fixture
 * (test/fixtures/bitmap-lookups, made by scripts/make-bitmap-lookups.py,
 * whose README describes what Mitsuba does); the CPU side (emission power per
 * triangle, the Mitsuba export) uses this one.
 *
 * - Texel (i, j) sits at ((i + 0.5) / W, (j + 0.5) / H); row 0 is the image's
 *   first (top) row, so (0, 0) is its top-left corner: no v flip.
 * - 8-bit colour is decoded from sRGB per texel, before filtering (Mitsuba
 *   decodes at the texel fetch); alpha is never decoded.
 */
import { srgbToLinear } from '../color';

export { srgbToLinear };

/** 8-bit RGBA, rows from top to bottom, not premultiplied. */
export interface RgbaImage {
  width: number;
  height: number;
  data: Uint8Array;
}

/** The scene format's `uv` transform: `uv' = T(offset) * R(rotation) * S(scale) * uv`, rotation in degrees. */
export interface UvTransform {
  offset: [number, number];
  scale: [number, number];
  rotation: number;
}

export interface LookupOptions {
  /** Decode R, G and B from sRGB (colour inputs of an 8-bit image); false reads every channel as stored. */
  srgb: boolean;
  transform?: UvTransform;
}

const STORED = Float64Array.from({ length: 256 }, (_, b) => b / 255);
const DECODED = STORED.map(srgbToLinear);

/**
 * `u' = ox + cos(r) sx u + sin(r) sy v`, `v' = oy - sin(r) sx u + cos(r) sy v`.
 * In Mitsuba: `to_uv = translate(offset) * rotate(-rotation) * scale(scale)`
 * (Mitsuba's 2-D rotate turns counter-clockwise, the format's clockwise).
 */
export function transformUv(uv: [number, number], t: UvTransform): [number, number] {
  const r = (t.rotation * Math.PI) / 180;
  const c = Math.cos(r);
  const s = Math.sin(r);
  const [u, v] = uv;
  return [
    t.offset[0] + c * t.scale[0] * u + s * t.scale[1] * v,
    t.offset[1] - s * t.scale[0] * u + c * t.scale[1] * v,
  ];
}

/** Euclidean modulo: Mitsuba's `repeat` for integer texel indices, negative ones included. */
function wrap(i: number, n: number): number {
  const m = i % n;
  return m < 0 ? m + n : m;
}

/** Texel position of a coordinate along one axis: the lower texel and the weight of the next one. */
function axis(coordinate: number, size: number): { lower: number; next: number; weight: number } {
  // A non-finite coordinate would put NaN into the result; read texel 0 instead.
  const x = Number.isFinite(coordinate) ? coordinate * size - 0.5 : -0.5;
  const floor = Math.floor(x);
  return { lower: wrap(floor, size), next: wrap(floor + 1, size), weight: x - floor };
}

/** The filtered RGBA value at `uv` (after `options.transform`), linear where `options.srgb` decodes. */
export function bitmapLookup(
  image: RgbaImage,
  uv: [number, number],
  options: LookupOptions,
): [number, number, number, number] {
  const { width, height, data } = image;
  if (!(width >= 1 && height >= 1 && data.length === width * height * 4)) {
    throw new Error(`bitmapLookup: ${width} x ${height} RGBA image needs ${width * height * 4} bytes, has ${data.length}`);
  }
  const [u, v] = options.transform ? transformUv(uv, options.transform) : uv;
  const x = axis(u, width);
  const y = axis(v, height);
  const corners: [number, number, number][] = [
    [x.lower, y.lower, (1 - x.weight) * (1 - y.weight)],
    [x.next, y.lower, x.weight * (1 - y.weight)],
    [x.lower, y.next, (1 - x.weight) * y.weight],
    [x.next, y.next, x.weight * y.weight],
  ];
  const out: [number, number, number, number] = [0, 0, 0, 0];
  for (const [i, j, w] of corners) {
    const base = (j * width + i) * 4;
    for (let c = 0; c < 4; c++) {
      const table = options.srgb && c < 3 ? DECODED : STORED;
      out[c] += w * table[data[base + c]];
    }
  }
  return out;
}
