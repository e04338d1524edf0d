/**
 * Constants of the Monte Carlo estimator shared by TypeScript and the trace
 * shader: sample validation, random-number dimensions, Russian roulette and
 * the low-discrepancy generators.
 */

/**
 * Samples whose radiance is not below this are treated as invalid (NaN and
 * Inf fail the test too). The schema allows emission up to 1e12 * 1e12 =
 * 1e24, so valid samples stay far below; float32 sums of 1e30-sized samples
 * still hold 3e8 of them.
 */
export const MAX_RADIANCE = 1e30;

/**
 * Random-number dimensions (one rand4() each): the camera ray takes one, each
 * bounce three (light sample, whose .w picks a caustic guide; BSDF sample,
 * whose .w picks the technique; Russian roulette).
 */
export const RNG_CAMERA_DIMENSIONS = 1;
export const RNG_BOUNCE_DIMENSIONS = 3;

/**
 * Russian roulette (PathTracerOptions.russianRoulette, off by default): from
 * this many scattering events on, a path whose throughput fell below the
 * threshold survives with probability = its largest throughput component.
 */
export const ROULETTE_DEPTH = 3;
export const ROULETTE_THRESHOLD = 0.95;

export type SamplerKind = 'kronecker' | 'independent';

/**
 * Generators of the R_d Kronecker sequence (M. Roberts, "The unreasonable
 * effectiveness of quasirandom sequences", 2018) for `n` coordinates:
 * alpha_j = frac(1 / phi^j), j = 1..n, phi the positive root of
 * x^(n+1) = x + 1; as 32-bit fixed point. The low-discrepancy sampler uses
 * six: camera jitter, first light sample, first BSDF sample (2D each).
 */
export function kroneckerGenerators(n: number): number[] {
  let phi = 2;
  for (let i = 0; i < 100; i++) phi = (1 + phi) ** (1 / (n + 1));
  return Array.from({ length: n }, (_, j) => Math.floor(((1 / phi ** (j + 1)) % 1) * 2 ** 32) >>> 0);
}

export function samplingDefines(sampler: SamplerKind, russianRoulette: boolean): Record<string, string | number> {
  const g = kroneckerGenerators(6);
  const pair = (i: number) => `uvec2(${g[2 * i]}u, ${g[2 * i + 1]}u)`;
  return {
    MAX_RADIANCE: MAX_RADIANCE.toExponential(),
    RNG_CAMERA_DIMENSIONS: `${RNG_CAMERA_DIMENSIONS}u`,
    RNG_BOUNCE_DIMENSIONS: `${RNG_BOUNCE_DIMENSIONS}u`,
    ROULETTE_DEPTH,
    ROULETTE_THRESHOLD: ROULETTE_THRESHOLD.toFixed(6),
    LD_GENERATOR_CAMERA: pair(0),
    LD_GENERATOR_LIGHT: pair(1),
    LD_GENERATOR_BSDF: pair(2),
    LOW_DISCREPANCY: sampler === 'kronecker' ? 1 : 0,
    RUSSIAN_ROULETTE: russianRoulette ? 1 : 0,
  };
}
