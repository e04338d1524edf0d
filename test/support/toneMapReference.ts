/**
 * Tone maps written from their published definitions, independently of
 * src/shaders/display.frag, to check it against known values:
 * - ACES: Stephen Hill's fit of the ACES RRT + ODT (BakingLab, ACES.hlsl):
 *   ACESInputMat, RRTAndODTFit, ACESOutputMat, then saturate.
 * - Khronos PBR Neutral: the reference GLSL of the Khronos specification
 *   (KhronosGroup/ToneMapping, PBR_Neutral).
 * - AgX: Benjamin Wrensch's "Minimal AgX" (agx_mat inset, log2 clamped to
 *   [-12.47393, 4.026069] EV, the 6th-order contrast fit, agx_mat_inv, then
 *   pow 2.2 to linear).
 * Matrices are written as their rows (published HLSL rows; the GLSL
 * sources' column-major mat3 constructor arguments transposed).
 */
type Rgb = [number, number, number];
type Rows = [Rgb, Rgb, Rgb];

const apply = (m: Rows, v: Rgb): Rgb => m.map((row) => row[0] * v[0] + row[1] * v[1] + row[2] * v[2]) as Rgb;

const ACES_INPUT: Rows = [[0.59719, 0.35458, 0.04823], [0.076, 0.90834, 0.01566], [0.0284, 0.13383, 0.83777]];
const ACES_OUTPUT: Rows = [[1.60475, -0.53108, -0.07367], [-0.10208, 1.10813, -0.00605], [-0.00327, -0.07276, 1.07602]];

export function acesHill(color: Rgb): Rgb {
  const v = apply(ACES_INPUT, color);
  const fit = v.map((x) => (x * (x + 0.0245786) - 0.000090537) / (x * (0.983729 * x + 0.432951) + 0.238081)) as Rgb;
  return apply(ACES_OUTPUT, fit);
}

export function khronosNeutral(color: Rgb): Rgb {
  const startCompression = 0.8 - 0.04;
  const desaturation = 0.15;
  const x = Math.min(...color);
  const offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
  const c = color.map((v) => v - offset) as Rgb;
  const peak = Math.max(...c);
  if (peak < startCompression) return c;
  const d = 1 - startCompression;
  const newPeak = 1 - (d * d) / (peak + d - startCompression);
  const g = 1 - 1 / (desaturation * (peak - newPeak) + 1);
  return c.map((v) => (v * newPeak) / peak * (1 - g) + newPeak * g) as Rgb;
}

const AGX_INSET: Rows = [
  [0.842479062253094, 0.0784335999999992, 0.0792237451477643],
  [0.0423282422610123, 0.878468636469772, 0.0791661274605434],
  [0.0423756549057051, 0.0784336, 0.879142973793104],
];
const AGX_OUTSET: Rows = [
  [1.19687900512017, -0.0980208811401368, -0.0990297440797205],
  [-0.0528968517574562, 1.15190312990417, -0.0989611768448433],
  [-0.0529716355144438, -0.0980434501171241, 1.15107367264116],
];

export function agxMinimal(color: Rgb): Rgb {
  const minEv = -12.47393;
  const maxEv = 4.026069;
  const encoded = apply(AGX_INSET, color).map((v) => {
    const ev = Math.min(maxEv, Math.max(minEv, Math.log2(v)));
    const x = (ev - minEv) / (maxEv - minEv);
    return 15.5 * x ** 6 - 40.14 * x ** 5 + 31.96 * x ** 4 - 6.868 * x ** 3 + 0.4298 * x ** 2 + 0.1191 * x - 0.00232;
  }) as Rgb;
  return apply(AGX_OUTSET, encoded).map((v) => Math.max(0, v) ** 2.2) as Rgb;
}

/** The sRGB transfer function (IEC 61966-2-1) after clamping to [0, 1], as 8 bits. */
export function srgb8(linear: number): number {
  const c = Math.min(1, Math.max(0, linear));
  const encoded = c <= 0.0031308 ? 12.92 * c : 1.055 * c ** (1 / 2.4) - 0.055;
  return Math.round(encoded * 255);
}
