/**
 * Property test of the environment map decoders: a fixture with random
 * bytes overwritten, or cut short, either decodes to an image of finite
 * texels of the header's size, or throws an AssetError, and
 * never anything else (no TypeError, RangeError or hang from a bad file).
 * It found the endless loop fixed in src/scene/envmap/vendor/EXRLoader.js.
 */
import { readFileSync } from 'node:fs';
import fc from 'fast-check';
import { afterAll, beforeAll, describe, expect, it, vi } from 'vitest';
import { decodeEnvironmentMap, MAX_ENVIRONMENT_HEIGHT, MAX_ENVIRONMENT_WIDTH } from '../../src/scene/envmap/decode';
import { AssetError } from '../../src/scene/assetError';

const DIR = new URL('../fixtures/envmaps/', import.meta.url);
const FILES = [
  'gradient-flat.hdr', 'gradient-rle.hdr', 'gradient-half-none.exr', 'gradient-float-zip.exr', 'gradient-half-zips.exr',
  'gradient-half-piz.exr', 'gradient-half-rle.exr', 'gradient-half-dwab.exr', 'gradient-half-dwaa.exr',
];

function decodeOrAssetError(bytes: Uint8Array, name: string): void {
  let image;
  try {
    image = decodeEnvironmentMap(bytes, name);
  } catch (error) {
    if (!(error instanceof AssetError)) throw new Error(`${name}: ${(error as Error).name}: ${(error as Error).message}`);
    return;
  }
  expect(image.width).toBeGreaterThan(0);
  expect(image.width).toBeLessThanOrEqual(MAX_ENVIRONMENT_WIDTH);
  expect(image.height).toBeLessThanOrEqual(MAX_ENVIRONMENT_HEIGHT);
  expect(image.rgb.length).toBe(image.width * image.height * 3);
  // Finite; negative texels may be kept (main keeps them, as Mitsuba does).
  for (const v of image.rgb) if (!Number.isFinite(v)) throw new Error(`${name}: texel ${v}`);
}

describe('decoders on damaged files', () => {
  // EXRLoader warns about every unknown header attribute a damaged name makes.
  beforeAll(() => void vi.spyOn(console, 'warn').mockImplementation(() => {}));
  afterAll(() => vi.restoreAllMocks());

  for (const name of FILES) {
    const original = new Uint8Array(readFileSync(new URL(name, DIR)));
    it(`${name}: overwritten bytes or a cut give an image or an AssetError`, () => {
      const damage = fc.record({
        writes: fc.array(fc.tuple(fc.nat({ max: original.length - 1 }), fc.integer({ min: 0, max: 255 })), { minLength: 1, maxLength: 8 }),
        cut: fc.option(fc.nat({ max: original.length }), { nil: undefined }),
      });
      fc.assert(
        fc.property(damage, ({ writes, cut }) => {
          const bytes = original.slice(0, cut ?? original.length);
          for (const [at, value] of writes) if (at < bytes.length) bytes[at] = value;
          decodeOrAssetError(bytes, name);
        }),
        { numRuns: 300, seed: 1234 },
      );
    });
  }
});
