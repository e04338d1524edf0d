/**
 * Environment map decoders: the same image written as .hdr (flat, RLE) and
 * .exr (half/float, each compression) by scripts/make-envmap-fixtures.py
 * decodes to the formula that made it; the shared maps decode to the texels
 * Mitsuba 3's Bitmap reads; every bad file is an AssetError.
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { decodeEnvironmentMap, MAX_ENVIRONMENT_HEIGHT, MAX_ENVIRONMENT_WIDTH } from '../../src/scene/envmap/decode';
import { AssetError } from '../../src/scene/assetError';
import { readExrHeader } from '../../src/scene/envmap/exr';
import type { EnvironmentImage } from '../../src/scene/types';

const DIR = new URL('../fixtures/envmaps/', import.meta.url);
const read = (name: string) => new Uint8Array(readFileSync(new URL(name, DIR)));
const decodeFixture = (name: string) => decodeEnvironmentMap(read(name), name);

const WIDTH = 24;
const HEIGHT = 12;
/** The formula of scripts/make-envmap-fixtures.py (row 0 on top). */
function gradient(x: number, y: number, c: number): number {
  if (x >= 4 && x < 12 && y >= 3 && y < 6) return [5, 2.5, 1.25][c];
  return 2 ** ((x - 10) / 2.5) * (1 + y / 4) * (c + 1) / 3;
}

/** Largest error of each texel channel relative to the texel's largest channel (RGBE shares one exponent). */
function worstError(image: EnvironmentImage): number {
  expect([image.width, image.height]).toEqual([WIDTH, HEIGHT]);
  let worst = 0;
  for (let y = 0; y < HEIGHT; y++) {
    for (let x = 0; x < WIDTH; x++) {
      const peak = Math.max(...[0, 1, 2].map((c) => gradient(x, y, c)));
      for (let c = 0; c < 3; c++) {
        worst = Math.max(worst, Math.abs(image.rgb[(y * WIDTH + x) * 3 + c] - gradient(x, y, c)) / peak);
      }
    }
  }
  return worst;
}

describe('decoders give the pixels that were written', () => {
  it('Radiance .hdr, flat and RLE scanlines: identical, within RGBE precision of the formula', () => {
    const flat = decodeFixture('gradient-flat.hdr');
    const rle = decodeFixture('gradient-rle.hdr');
    expect(rle.rgb).toEqual(flat.rgb);
    // 8-bit mantissas: the largest channel is off by < 2^-7 of itself (truncation).
    expect(worstError(flat)).toBeLessThan(2 ** -7);
    expect(worstError(flat)).toBeGreaterThan(0); // truly RGBE-quantized, not a copy of the formula
  });

  const lossless = ['none', 'rle', 'zips', 'zip', 'piz'];
  for (const compression of lossless) {
    it(`OpenEXR ${compression}: half within half precision, float exact to float32`, () => {
      expect(worstError(decodeFixture(`gradient-half-${compression}.exr`))).toBeLessThan(2 ** -11);
      expect(worstError(decodeFixture(`gradient-float-${compression}.exr`))).toBeLessThan(2 ** -23);
    });
  }

  it('every lossless OpenEXR compression gives the same half texels', () => {
    const reference = decodeFixture('gradient-half-none.exr').rgb;
    for (const compression of lossless) expect(decodeFixture(`gradient-half-${compression}.exr`).rgb).toEqual(reference);
  });

  for (const compression of ['dwaa', 'dwab']) {
    it(`OpenEXR ${compression} (lossy DCT): as OpenEXR itself decodes it, and close to the formula`, () => {
      const image = decodeFixture(`gradient-half-${compression}.exr`);
      const raw = readFileSync(new URL(`gradient-half-${compression}.openexr.f32`, DIR));
      const openexr = new Float32Array(raw.buffer.slice(raw.byteOffset, raw.byteOffset + raw.byteLength));
      expect(openexr.length).toBe(image.rgb.length);
      let worst = 0;
      for (let i = 0; i < openexr.length; i++) worst = Math.max(worst, Math.abs(image.rgb[i] - openexr[i]) / Math.max(openexr[i], 1e-3));
      expect(worst).toBeLessThan(4e-3); // half-float rounding of the DCT output; measured on the CC0 maps of @pmndrs/assets: 0.26 %
      expect(worstError(image)).toBeLessThan(0.05);
    });
  }

  // Texels as Mitsuba 3's Bitmap reads them (mi.Bitmap(path), row 0 on top).
  it('the shared sunset.hdr (RLE) reads as Mitsuba reads it', () => {
    const image = decodeFixture('sunset.hdr');
    expect([image.width, image.height]).toEqual([512, 256]);
    expect(Array.from(image.rgb.subarray(0, 6))).toEqual([0.25, 0.41796875, 0.7734375, 0.24609375, 0.41796875, 0.7734375]);
    expect(Array.from(image.rgb.subarray(image.rgb.length - 3))).toEqual([0.103515625, 0.09716796875, 0.10009765625]);
  });

  it('the shared studio.exr (half, PIZ) reads as Mitsuba reads it', () => {
    const image = decodeFixture('studio.exr');
    expect([image.width, image.height]).toEqual([512, 256]);
    const first = [0.006103515625, 0.007137298583984375, 0.0086212158203125];
    const last = [0.52734375, 0.630859375, 0.7041015625];
    expect(Array.from(image.rgb.subarray(0, 3))).toEqual(first);
    expect(Array.from(image.rgb.subarray(image.rgb.length - 3))).toEqual(last);
    const max = image.rgb.reduce((a, b) => Math.max(a, b), 0);
    const mean = image.rgb.reduce((a, b) => a + b, 0) / image.rgb.length;
    expect(max).toBe(3730);
    // studio.exr holds 2028 negative texels (down to -149.25); Mitsuba keeps
    // them and so does the decoder: the mean is Mitsuba's.
    expect(mean).toBeCloseTo(1.8839068828277352, 6);
    expect(image.rgb.reduce((a, b) => Math.min(a, b), 0)).toBe(-149.25);
  });
});

function expectAssetError(bytes: Uint8Array, name: string, pattern: RegExp): void {
  let thrown: unknown;
  try {
    decodeEnvironmentMap(bytes, name);
  } catch (error) {
    thrown = error;
  }
  expect(thrown, `${name} must be rejected`).toBeInstanceOf(AssetError);
  expect((thrown as Error).message).toMatch(pattern);
  expect((thrown as Error).message).not.toMatch(/environment\.map/);
}

function replaceText(bytes: Uint8Array, from: string, to: string): Uint8Array {
  const text = Buffer.from(bytes).toString('latin1');
  expect(text.includes(from)).toBe(true);
  return new Uint8Array(Buffer.from(text.replace(from, to), 'latin1'));
}

/** The dataWindow attribute's value (4 int32: xMin, yMin, xMax, yMax) in an EXR header. */
function withDataWindow(bytes: Uint8Array, xMax: number, yMax: number): Uint8Array {
  const copy = bytes.slice();
  const at = Buffer.from(copy).indexOf('dataWindow\0box2i\0') + 'dataWindow\0box2i\0'.length + 4;
  const view = new DataView(copy.buffer);
  view.setInt32(at + 8, xMax, true);
  view.setInt32(at + 12, yMax, true);
  return copy;
}

describe('bad files are AssetErrors', () => {
  it('empty files', () => {
    expectAssetError(new Uint8Array(0), 'sky.hdr', /empty/);
    expectAssetError(new Uint8Array(0), 'sky.exr', /empty/);
  });

  it('files that are neither format', () => {
    expectAssetError(new TextEncoder().encode('P6\n2 2\n255\n'), 'sky.png', /neither an OpenEXR/);
    expectAssetError(new TextEncoder().encode('hello'), 'sky.hdr', /not a Radiance/);
    expectAssetError(new TextEncoder().encode('hello'), 'sky.exr', /not an OpenEXR/);
  });

  it('truncated .hdr files (flat, RLE, in the header)', () => {
    for (const name of ['gradient-flat.hdr', 'gradient-rle.hdr', 'sunset.hdr']) {
      const bytes = read(name);
      expectAssetError(bytes.subarray(0, bytes.length - 1), name, /truncated/);
      expectAssetError(bytes.subarray(0, Math.floor(bytes.length / 2)), name, /truncated/);
      expectAssetError(bytes.subarray(0, 30), name, /truncated/);
    }
  });

  it('corrupt .hdr headers and scanlines', () => {
    const rle = read('gradient-rle.hdr');
    expectAssetError(replaceText(rle, 'FORMAT=32-bit_rle_rgbe', 'FORMAT=32-bit_rle_xyze'), 'a.hdr', /pixel format/);
    expectAssetError(replaceText(rle, '-Y 12 +X 24', '+Y 12 -X 24'), 'a.hdr', /size line/);
    expectAssetError(replaceText(rle, '#?RADIANCE', '#?NONSENSE'), 'a.hdr', /not a Radiance/);
    const badRun = rle.slice();
    const firstScanline = Buffer.from(rle).indexOf('+X 24\n') + 6;
    badRun[firstScanline + 4] = 0; // a run of length 0
    expectAssetError(badRun, 'a.hdr', /corrupt/);
    const badWidth = rle.slice();
    badWidth[firstScanline + 3] = 25; // the scanline says 25 texels wide
    expectAssetError(badWidth, 'a.hdr', /corrupt/);
  });

  it('absurdly sized .hdr files are refused from the header', () => {
    const rle = read('gradient-rle.hdr');
    expectAssetError(replaceText(rle, '-Y 12 +X 24', '-Y 100000 +X 200000'), 'a.hdr', /larger than the maximum/);
    expectAssetError(replaceText(rle, '-Y 12 +X 24', `-Y ${MAX_ENVIRONMENT_HEIGHT} +X ${MAX_ENVIRONMENT_WIDTH + 1}`), 'a.hdr', /maximum/);
    expectAssetError(replaceText(rle, '-Y 12 +X 24', '-Y 0 +X 24'), 'a.hdr', /positive/);
  });

  it('truncated .exr files (every compression, in the header, the table and the pixels)', () => {
    for (const name of ['gradient-half-none.exr', 'gradient-float-zip.exr', 'gradient-half-piz.exr', 'gradient-half-dwab.exr', 'studio.exr']) {
      const bytes = read(name);
      expectAssetError(bytes.subarray(0, bytes.length - 1), name, /truncated/);
      expectAssetError(bytes.subarray(0, Math.floor(bytes.length * 0.6)), name, /truncated/);
      expectAssetError(bytes.subarray(0, 40), name, /truncated/);
      expectAssetError(bytes.subarray(0, 6), name, /truncated/);
    }
  });

  it('corrupt .exr files', () => {
    const zip = read('gradient-half-zip.exr');
    const badMagic = zip.slice();
    badMagic[0] = 0x77;
    expectAssetError(badMagic, 'a.exr', /not an OpenEXR/);
    // Garbage in place of the zlib stream of the first chunk.
    const garbage = zip.slice();
    const { tableStart } = readExrHeader(garbage);
    const chunk = Number(new DataView(garbage.buffer).getBigUint64(tableStart, true));
    for (let i = chunk + 8; i < chunk + 40; i++) garbage[i] = (i * 37) & 255;
    expectAssetError(garbage, 'a.exr', /corrupt/);
    expectAssetError(replaceText(zip, '\0R\0', '\0X\0'), 'a.exr', /no R, G, B/);
  });

  it('absurdly sized .exr files are refused from the header', () => {
    const exr = read('gradient-half-zip.exr');
    expectAssetError(withDataWindow(exr, 99999, 49999), 'a.exr', /larger than the maximum/);
    expectAssetError(withDataWindow(exr, MAX_ENVIRONMENT_WIDTH, 11), 'a.exr', /larger than the maximum/);
    expectAssetError(withDataWindow(exr, -5, 11), 'a.exr', /positive/);
  });
});

describe('invalid texels', () => {
  it('NaN and infinite texels decode to 0; negative and the other texels are untouched', () => {
    const bytes = read('gradient-float-none.exr');
    const { tableStart } = readExrHeader(bytes);
    const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    const chunk = Number(view.getBigUint64(tableStart, true));
    // Uncompressed scanline 0: y, size, then the B plane (channels sorted by name).
    [NaN, -1, Infinity, -Infinity].forEach((v, x) => view.setFloat32(chunk + 8 + x * 4, v, true));
    const image = decodeEnvironmentMap(bytes, 'nan.exr');
    for (const x of [0, 2, 3]) expect(image.rgb[x * 3 + 2]).toBe(0);
    expect(image.rgb[1 * 3 + 2]).toBe(-1);
    expect(image.rgb[4 * 3 + 2]).toBeCloseTo(gradient(4, 0, 2), 5);
    expect(image.rgb[0]).toBeCloseTo(gradient(0, 0, 0), 5);
  });
});
