/** Tone mapping operators of the display pass, by name (display.frag switches on their index). */
export const TONEMAPS = ['none', 'aces', 'neutral', 'agx'] as const;
export type ToneMap = (typeof TONEMAPS)[number];

export function toneMapDefines(): Record<string, number> {
  return Object.fromEntries(TONEMAPS.map((name, i) => [`TONEMAP_${name.toUpperCase()}`, i]));
}
