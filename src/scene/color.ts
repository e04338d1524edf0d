/**
 * Color conversions. The scene format stores linear RGB; a color may also be
 * written as "#rrggbb", which is sRGB-encoded and converted here with the
 * exact piecewise sRGB transfer function (IEC 61966-2-1), not a 2.2 gamma.
 */
import type { Vec3 } from './types';

/** "#rrggbb": exactly six hex digits, either case. */
export const HEX_COLOR_PATTERN = /^#[0-9a-f]{6}$/i;

/** sRGB-encoded value -> linear. The linear segment also covers c < 0. */
export function srgbToLinear(c: number): number {
  return c <= 0.04045 ? c / 12.92 : Math.pow((c + 0.055) / 1.055, 2.4);
}

/** Linear value -> sRGB-encoded. Inverse of `srgbToLinear`; values above 1 follow the power curve. */
export function linearToSrgb(c: number): number {
  return c <= 0.0031308 ? 12.92 * c : 1.055 * Math.pow(c, 1 / 2.4) - 0.055;
}

export function isHexColor(value: unknown): value is string {
  return typeof value === 'string' && HEX_COLOR_PATTERN.test(value);
}

/**
 * "#rrggbb" (sRGB) -> linear RGB; "#ffffff" -> [1, 1, 1], "#808080" -> 0.2158605...
 * @throws RangeError when `hex` is not exactly "#" and six hex digits.
 */
export function hexToLinear(hex: string): Vec3 {
  if (!isHexColor(hex)) throw new RangeError(`not a "#rrggbb" color: ${String(hex).slice(0, 20)}`);
  const channel = (offset: number) => srgbToLinear(parseInt(hex.slice(offset, offset + 2), 16) / 255);
  return [channel(1), channel(3), channel(5)];
}

/**
 * Linear RGB -> "#rrggbb" (lower case). Each channel is clamped to [0, 1]
 * (NaN counts as 0) and rounded to the nearest 8-bit sRGB value, so
 * `linearToHex(hexToLinear(h)) === h.toLowerCase()` for every valid `h`.
 */
export function linearToHex(color: Vec3): string {
  const byte = (c: number) => {
    const clamped = c > 0 ? Math.min(c, 1) : 0;
    return Math.round(linearToSrgb(clamped) * 255).toString(16).padStart(2, '0');
  };
  return `#${byte(color[0])}${byte(color[1])}${byte(color[2])}`;
}
