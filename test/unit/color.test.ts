import { describe, expect, it } from 'vitest';
import { HEX_COLOR_PATTERN, hexToLinear, linearToHex, linearToSrgb, srgbToLinear } from '../../src/scene';

/** The sRGB transfer function as IEC 61966-2-1 writes it. */
const reference = (c: number) => (c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4);

describe('srgbToLinear / linearToSrgb', () => {
  it('fixes 0 and 1', () => {
    expect(srgbToLinear(0)).toBe(0);
    expect(srgbToLinear(1)).toBe(1);
    expect(linearToSrgb(0)).toBe(0);
    expect(linearToSrgb(1)).toBeCloseTo(1, 15);
  });

  it('is the exact piecewise function, not a gamma curve', () => {
    expect(srgbToLinear(0.5)).toBeCloseTo(0.214041140482232, 14);
    expect(srgbToLinear(0.04045)).toBeCloseTo(0.04045 / 12.92, 16); // linear segment up to the knee
    expect(srgbToLinear(0.02)).toBe(0.02 / 12.92);
    expect(linearToSrgb(0.001)).toBeCloseTo(0.01292, 15);
    expect(srgbToLinear(0.5)).not.toBeCloseTo(0.5 ** 2.2, 3);
  });

  it("is continuous at the knees (up to the standard's rounded constants)", () => {
    expect(srgbToLinear(0.04045 + 1e-12)).toBeCloseTo(srgbToLinear(0.04045), 8);
    expect(linearToSrgb(0.0031308 + 1e-12)).toBeCloseTo(linearToSrgb(0.0031308), 7);
  });

  it('inverts itself over [0, 1]', () => {
    for (let i = 0; i <= 1000; i++) {
      const c = i / 1000;
      expect(linearToSrgb(srgbToLinear(c))).toBeCloseTo(c, 12);
      expect(srgbToLinear(linearToSrgb(c))).toBeCloseTo(c, 12);
    }
  });

  it('increases monotonically', () => {
    let previous = -Infinity;
    for (let i = 0; i <= 1000; i++) {
      const value = srgbToLinear(i / 1000);
      expect(value).toBeGreaterThan(previous);
      previous = value;
    }
  });
});

describe('hexToLinear', () => {
  it('converts exactly', () => {
    expect(hexToLinear('#ffffff')).toEqual([1, 1, 1]);
    expect(hexToLinear('#000000')).toEqual([0, 0, 0]);
    const [r, g, b] = hexToLinear('#808080');
    expect(r).toBeCloseTo(0.21586050011389926, 15);
    expect(g).toBe(r);
    expect(b).toBe(r);
    expect(hexToLinear('#ff8000')).toEqual([1, reference(128 / 255), 0]);
  });

  it('reads each channel from its own pair of digits', () => {
    expect(hexToLinear('#0a1b2c')).toEqual([reference(10 / 255), reference(27 / 255), reference(44 / 255)]);
  });

  it('ignores case', () => {
    expect(hexToLinear('#ABCDEF')).toEqual(hexToLinear('#abcdef'));
    expect(hexToLinear('#aBcDeF')).toEqual(hexToLinear('#abcdef'));
  });

  it.each(['fff', '#fff', '#ffff', '#fffffff', 'ffffff', '#gggggg', ' #ffffff', '#ffffff ', '#ff ffff', '', '#'])(
    'rejects %j with a RangeError',
    (bad) => {
      expect(HEX_COLOR_PATTERN.test(bad)).toBe(false);
      expect(() => hexToLinear(bad)).toThrow(RangeError);
    },
  );
});

describe('linearToHex', () => {
  it('round-trips every 8-bit value', () => {
    for (let v = 0; v < 256; v++) {
      const hex = `#${v.toString(16).padStart(2, '0')}${(255 - v).toString(16).padStart(2, '0')}00`;
      expect(linearToHex(hexToLinear(hex))).toBe(hex);
    }
  });

  it('writes lower case', () => {
    expect(linearToHex(hexToLinear('#ABCDEF'))).toBe('#abcdef');
  });

  it('clamps out-of-range and NaN channels', () => {
    expect(linearToHex([2, -1, NaN])).toBe('#ff0000');
    expect(linearToHex([Infinity, -Infinity, 0.5])).toBe(`#ff00${Math.round(linearToSrgb(0.5) * 255).toString(16)}`);
  });
});
