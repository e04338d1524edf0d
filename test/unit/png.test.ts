import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { decodePng, encodePng } from '../../src/cli/png';

function pattern(width: number, height: number): Uint8Array {
  const rgba = new Uint8Array(width * height * 4);
  for (let i = 0; i < rgba.length; i++) rgba[i] = (i * 37 + 11) & 0xff;
  return rgba;
}

describe('encodePng / decodePng', () => {
  it('writes a PNG signature and round-trips RGBA8 exactly', () => {
    const rgba = pattern(7, 3);
    const png = encodePng(7, 3, rgba);
    expect(png.subarray(0, 8)).toEqual(Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]));
    const image = decodePng(png);
    expect([image.width, image.height]).toEqual([7, 3]);
    expect(Buffer.from(image.rgba)).toEqual(Buffer.from(rgba));
  });

  it('keeps row 0 at the top', () => {
    const rgba = new Uint8Array(1 * 2 * 4);
    rgba.set([255, 0, 0, 255], 0); // top: red
    rgba.set([0, 0, 255, 255], 4); // bottom: blue
    const image = decodePng(encodePng(1, 2, rgba));
    expect(Array.from(image.rgba)).toEqual([255, 0, 0, 255, 0, 0, 255, 255]);
  });

  it('is deterministic: same pixels, same bytes', () => {
    const rgba = pattern(16, 16);
    expect(encodePng(16, 16, rgba).equals(encodePng(16, 16, rgba.slice()))).toBe(true);
  });

  it('accepts a subarray view of a larger buffer', () => {
    const big = pattern(4, 4);
    const view = big.subarray(16, 16 + 2 * 2 * 4);
    expect(Buffer.from(decodePng(encodePng(2, 2, view)).rgba)).toEqual(Buffer.from(view));
  });

  it('rejects a pixel array of the wrong length', () => {
    expect(() => encodePng(2, 2, new Uint8Array(15))).toThrow(/16 RGBA bytes/);
  });

  it('reads the reference previews in the fixtures', () => {
    const image = decodePng(readFileSync(new URL('../fixtures/references/seed.png', import.meta.url)));
    expect([image.width, image.height]).toEqual([256, 192]);
    expect(image.rgba.length).toBe(256 * 192 * 4);
  });
});
