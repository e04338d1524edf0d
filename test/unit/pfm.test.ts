import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { decodePfm, encodePfm } from '../../src/image/pfm';

/** A small RGBA float image whose every value says where it came from. */
function ramp(width: number, height: number): Float32Array {
  const rgba = new Float32Array(width * height * 4);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const i = (y * width + x) * 4;
      rgba.set([x + 0.25, y + 0.5, x * 10 + y + 0.125, 1], i);
    }
  }
  return rgba;
}

describe('encodePfm', () => {
  it('writes the colour PFM header with a little-endian scale', () => {
    const pfm = Buffer.from(encodePfm(3, 2, ramp(3, 2)));
    expect(pfm.subarray(0, 12).toString('latin1')).toBe('PF\n3 2\n-1.0\n');
    expect(pfm.length).toBe(12 + 3 * 2 * 3 * 4);
  });

  it('stores rows bottom to top and drops alpha', () => {
    const pfm = Buffer.from(encodePfm(3, 2, ramp(3, 2)));
    const body = pfm.subarray(12);
    // The first stored pixel is the image's bottom-left (x 0, y 1).
    expect([body.readFloatLE(0), body.readFloatLE(4), body.readFloatLE(8)]).toEqual([0.25, 1.5, 1.125]);
    // The last stored pixel is the image's top-right (x 2, y 0).
    const last = body.length - 12;
    expect([body.readFloatLE(last), body.readFloatLE(last + 4), body.readFloatLE(last + 8)]).toEqual([2.25, 0.5, 20.125]);
  });

  it('rejects a pixel array of the wrong length and bad sizes', () => {
    expect(() => encodePfm(2, 2, new Float32Array(15))).toThrow(/16 RGBA floats/);
    expect(() => encodePfm(0, 2, new Float32Array(0))).toThrow(/size/);
  });
});

describe('decodePfm', () => {
  it('round-trips encodePfm exactly, including non-finite values', () => {
    const rgba = ramp(5, 4);
    rgba[0] = Infinity;
    rgba[5] = -0.5;
    rgba[6] = 1e-30;
    const { width, height, rgb, scale } = decodePfm(encodePfm(5, 4, rgba));
    expect([width, height, scale]).toEqual([5, 4, 1]);
    for (let p = 0; p < 20; p++) {
      expect([rgb[p * 3], rgb[p * 3 + 1], rgb[p * 3 + 2]]).toEqual([rgba[p * 4], rgba[p * 4 + 1], rgba[p * 4 + 2]]);
    }
  });

  it('reads big-endian and greyscale files', () => {
    // 1x2 greyscale, big endian (positive scale): stored bottom (2.0) then top (1.0).
    const body = Buffer.alloc(8);
    body.writeFloatBE(2, 0);
    body.writeFloatBE(1, 4);
    const image = decodePfm(Buffer.concat([Buffer.from('Pf\n1 2\n1.0\n'), body]));
    expect(Array.from(image.rgb)).toEqual([1, 1, 1, 2, 2, 2]);
  });

  it('reads the Mitsuba reference images in the fixtures', () => {
    const image = decodePfm(readFileSync(new URL('../fixtures/references/seed.pfm', import.meta.url)));
    expect([image.width, image.height]).toEqual([256, 192]);
    expect(image.rgb.length).toBe(256 * 192 * 3);
    expect(image.rgb.every((v) => Number.isFinite(v) && v >= 0)).toBe(true);
    // The sky at the top of the frame is the bluish environment.
    const top = image.rgb.subarray(0, 3);
    expect(top[2]).toBeGreaterThan(top[0]);
  });

  it('rejects files that are not PFM or are truncated', () => {
    expect(() => decodePfm(Buffer.from('P6\n1 1\n255\nabc'))).toThrow(/not a PFM/);
    expect(() => decodePfm(Buffer.from('PF\n2 2\n-1.0\n\0\0\0\0'))).toThrow(/truncated/);
    expect(() => decodePfm(Buffer.from('PF\n2'))).toThrow(/header/);
    expect(() => decodePfm(Buffer.from('PF\n0 2\n-1.0\n'))).toThrow(/width/);
  });
});
