/**
 * The reference texture lookup against Mitsuba 3.9.1's `bitmap` texture on
 * the fixture of scripts/make-bitmap-lookups.py (test/fixtures/bitmap-lookups).
 *
 * Tolerance, per lookup: Mitsuba works in float32. Its texel position
 * `u' W - 0.5` (after a float32 `to_uv`) is off by a few ulps of
 * `|u'| W + |v'| H`, which moves the filtered value by at most that times the
 * largest texel difference (<= 1); its sRGB decode is a rational fit within
 * 2.4e-6 relative of the exact curve (measured over all 256 values). So
 * `|ours - Mitsuba| <= 1e-5 |Mitsuba| + 8 * 2^-24 * (|u'| W + |v'| H + 1)`.
 */
import { readFileSync } from 'node:fs';
import { decode } from 'fast-png';
import { describe, expect, it } from 'vitest';
import { bitmapLookup, srgbToLinear, transformUv, type LookupOptions, type RgbaImage, type UvTransform } from './bitmapLookup';

interface Lookup {
  group: 'srgb' | 'raw' | 'channel' | 'transform';
  srgb: boolean;
  channel?: 'r' | 'g' | 'b' | 'a';
  uv: [number, number];
  transform?: UvTransform;
  mitsuba: number[];
}

interface Fixture {
  image: { file: string; width: number; height: number; rgba: number[] };
  channelImages: Record<'r' | 'g' | 'b' | 'a', string>;
  lookups: Lookup[];
}

const DIR = new URL('../../../test/fixtures/bitmap-lookups/', import.meta.url);
const fixture = JSON.parse(readFileSync(new URL('lookups.json', DIR), 'utf8')) as Fixture;
const image: RgbaImage = {
  width: fixture.image.width,
  height: fixture.image.height,
  data: Uint8Array.from(fixture.image.rgba),
};
const CHANNELS = ['r', 'g', 'b', 'a'] as const;

type LookupFn = (image: RgbaImage, uv: [number, number], options: LookupOptions) => number[];

/** Our value of one lookup, in the channels Mitsuba returned. */
function ours(lookup: Lookup, fn: LookupFn = bitmapLookup): number[] {
  const value = fn(image, lookup.uv, { srgb: lookup.srgb, transform: lookup.transform });
  return lookup.channel ? [value[CHANNELS.indexOf(lookup.channel)]] : value.slice(0, 3);
}

/** The largest error of a lookup function over the fixture, in units of each lookup's tolerance. */
function worstError(lookups: Lookup[], fn: LookupFn = bitmapLookup): number {
  let worst = 0;
  for (const lookup of lookups) {
    const [u, v] = lookup.transform ? transformUv(lookup.uv, lookup.transform) : lookup.uv;
    const position = 8 * 2 ** -24 * (Math.abs(u) * image.width + Math.abs(v) * image.height + 1);
    const value = ours(lookup, fn);
    expect(value).toHaveLength(lookup.mitsuba.length);
    lookup.mitsuba.forEach((m, c) => {
      worst = Math.max(worst, Math.abs(value[c] - m) / (1e-5 * Math.abs(m) + position));
    });
  }
  return worst;
}

const group = (name: Lookup['group']) => fixture.lookups.filter((l) => l.group === name);

describe('bitmapLookup against Mitsuba bitmap', () => {
  it('reads the PNGs Mitsuba read: the RGBA texels as listed, each channel image its channel', () => {
    const png = decode(readFileSync(new URL(fixture.image.file, DIR)));
    expect([png.width, png.height, png.channels, png.depth]).toEqual([image.width, image.height, 4, 8]);
    expect(Array.from(png.data)).toEqual(fixture.image.rgba);
    CHANNELS.forEach((name, c) => {
      const grey = decode(readFileSync(new URL(fixture.channelImages[name], DIR)));
      expect(grey.channels).toBe(1);
      expect(Array.from(grey.data)).toEqual(fixture.image.rgba.filter((_, i) => i % 4 === c));
    });
  });

  it.each(['srgb', 'raw', 'channel', 'transform'] as const)('%s lookups equal Mitsuba within float32 tolerance', (name) => {
    const lookups = group(name);
    expect(lookups.length).toBeGreaterThanOrEqual(10);
    expect(worstError(lookups)).toBeLessThanOrEqual(1);
  });

  it('the fixture tells the conventions apart: v flip, half-texel shift, filtering after decoding, rotation sign', () => {
    const flipV: LookupFn = (img, [u, v], o) => bitmapLookup(img, [u, 1 - v], o);
    const noHalfTexel: LookupFn = (img, [u, v], o) =>
      bitmapLookup(img, [u + 0.5 / img.width, v + 0.5 / img.height], o);
    const decodeAfterFilter: LookupFn = (img, uv, o) =>
      bitmapLookup(img, uv, { ...o, srgb: false }).map((x, c) => (o.srgb && c < 3 ? srgbToLinear(x) : x));
    const otherSign: LookupFn = (img, uv, o) =>
      bitmapLookup(img, uv, { ...o, transform: o.transform && { ...o.transform, rotation: -o.transform.rotation } });
    for (const wrong of [flipV, noHalfTexel, decodeAfterFilter]) {
      expect(worstError(group('srgb'), wrong)).toBeGreaterThan(100);
    }
    expect(worstError(group('transform'), otherSign)).toBeGreaterThan(100);
  });

  it('srgbToLinear is the exact piecewise sRGB curve', () => {
    expect(srgbToLinear(0)).toBe(0);
    expect(srgbToLinear(1)).toBeCloseTo(1, 15);
    expect(srgbToLinear(0.04045)).toBeCloseTo(0.04045 / 12.92, 15);
    expect(srgbToLinear(0.5)).toBeCloseTo(0.21404114048223255, 15);
  });

  it('keeps non-finite coordinates finite and rejects a data array of the wrong size', () => {
    for (const uv of [[NaN, 0.5], [Infinity, -Infinity], [1e30, -1e30]] as [number, number][]) {
      expect(bitmapLookup(image, uv, { srgb: true }).every(Number.isFinite)).toBe(true);
    }
    expect(() => bitmapLookup({ ...image, data: image.data.subarray(4) }, [0, 0], { srgb: false })).toThrow(/needs 60 bytes, has 56/);
  });
});
