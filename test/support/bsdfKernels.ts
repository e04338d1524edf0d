/**
 * The checks Mitsuba runs on every BSDF plugin, on the shader's own code
 * through the headless kernels (src/headless/kernels.ts, guideKernels.ts):
 * a chi-square test of a material's sampler against its pdf, and the mean
 * of its sample weights (f |cos| / pdf, the directional albedo).
 */
import { expect } from 'vitest';
import type { RenderSession } from '../../src/node/session';
import type { Material, Vec3 } from '../../src/scene/types';
import { chiSquareTest, type ChiSquareResult } from './chi2';
import { expectedCounts, sphereBin } from './sphereHistogram';

const SAMPLES_SIDE = 512; // 262,144 samples per chi-square test
const WEIGHT_SIDE = 256; // 65,536 samples per albedo

export interface SamplerCheck {
  chiSquare: ChiSquareResult;
  /** The pdf's integral over the sphere (midpoint rule) and the share of valid samples: equal for a correct sampler. */
  mass: number;
  validFraction: number;
  /** Valid samples below the surface (a one-sided BSDF has none). */
  belowHorizon: number;
}

export interface SamplerOptions {
  /** Pdf points per bin side (midpoint rule): 16 by default; sharp features (a refraction lobe's Jacobian) need more. */
  sub?: number;
}

/**
 * Samples `material` seen from `wo` and bins the directions over the whole
 * sphere (reflection and transmission alike) against the pdf integrated per bin.
 */
export async function samplerChiSquare(session: RenderSession, material: Material, wo: Vec3, seed = 5, options: SamplerOptions = {}): Promise<SamplerCheck> {
  const bins = { cosBins: 20, phiBins: 40 };
  const sub = options.sub ?? 16;
  const n = SAMPLES_SIDE * SAMPLES_SIDE;
  const samples = await session.runKernel({ kernel: 'sampleMaterial', width: SAMPLES_SIDE, height: SAMPLES_SIDE, material, wo, seed });
  const grid = await session.runKernel({ kernel: 'pdfMaterial', width: bins.phiBins * sub, height: bins.cosBins * sub, material, wo });
  const { expected, mass } = expectedCounts(grid, 3, bins, sub, n);
  const observed = new Float64Array(expected.length);
  let valid = 0;
  let belowHorizon = 0;
  for (let i = 0; i < n; i++) {
    const [x, y, z, pdf] = samples.subarray(i * 4, i * 4 + 4);
    if (pdf === 0) continue; // no sample: the pdf has no mass there either
    if (z <= 0) belowHorizon++;
    valid++;
    observed[sphereBin(x, y, z, bins)]++;
  }
  return { chiSquare: chiSquareTest(observed, expected), mass, validFraction: valid / n, belowHorizon };
}

/** Significance of each chi-square test: with tens of them, false failures stay rare. */
const ALPHA = 1e-4;

/** What a one-sided BSDF's sampler must show: samples above the surface only, distributed as its pdf. */
export function expectSamplerMatchesPdf(result: SamplerCheck): void {
  expect(result.belowHorizon).toBe(0);
  expect(result.validFraction, 'most samples must be valid').toBeGreaterThan(0.5);
  // VNDF samples reflected below the horizon are dropped: the pdf's mass is the valid share.
  expect(Math.abs(result.mass - result.validFraction)).toBeLessThan(0.01);
  expect(result.chiSquare.degreesOfFreedom).toBeGreaterThan(20);
  expect(result.chiSquare.pValue, JSON.stringify(result)).toBeGreaterThan(ALPHA);
}

export interface WeightCheck {
  /** Mean of channel 0 of the sample weights over all draws (invalid ones count 0), and its standard error. */
  mean: number;
  standardError: number;
  /** Largest relative difference between a sample's weight and bsdfEval / bsdfPdf at its direction. */
  worstRatioError: number;
}

export async function bsdfWeights(session: RenderSession, material: Material, wo: Vec3, seed = 13): Promise<WeightCheck> {
  const n = WEIGHT_SIDE * WEIGHT_SIDE;
  // (weight, valid, bsdfEval / bsdfPdf at the sample, pdf) per sample.
  const samples = await session.runKernel({ kernel: 'weightBsdf', width: WEIGHT_SIDE, height: WEIGHT_SIDE, material, wo, seed });
  let sum = 0;
  let sumSq = 0;
  let worst = 0;
  for (let i = 0; i < n; i++) {
    const [weight, valid, ratio, pdf] = samples.subarray(i * 4, i * 4 + 4);
    if (valid === 0) continue;
    if (pdf > 0) worst = Math.max(worst, Math.abs(weight - ratio) / Math.max(1e-6, Math.abs(ratio)));
    sum += weight;
    sumSq += weight * weight;
  }
  const mean = sum / n;
  return { mean, standardError: Math.sqrt(Math.max(0, sumSq / n - mean * mean) / n), worstRatioError: worst };
}
