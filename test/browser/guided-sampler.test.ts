import type { Material } from '../../src/scene/types';
/**
 * The caustic-guide mixture (src/shaders/lights/caustic_guide.glsl) on its
 * own, in the browser: one guide (a mirror sphere and a light) written into
 * the SceneBlock uniform block, buildGuides() making the cone at a vertex,
 * then sampleGuided() against guidedPdf():
 * - guidedPdf on a grid over the sphere equals (1 - p) bsdfPdf + p / cone
 *   solid angle inside the cone (cone and p read back from the shader);
 * - chi-square of sampleGuided's directions against that mixture, the cone
 *   part integrated over each bin in TypeScript (exact up to a fine
 *   quadrature), the BSDF part from the shader's own pdf grid;
 * - every sample's weight is f / mixture pdf, and its mean (a moment test)
 *   equals the integral of f |cos|: the mixture is unbiased.
 * Until now the mixture was checked only end to end (image references).
 */
import { describe, expect, it } from 'vitest';
import { chiSquareTest } from '../support/chi2';
import { useRenderSession } from '../support/browser';
import { expectedCounts, gridDirection, sphereBin, type SphereBins } from '../support/sphereHistogram';

const SAMPLES_SIDE = 512;
const ALPHA = 1e-4;
const BINS: SphereBins = { cosBins: 20, phiBins: 40 };
const SUB = 16;
/** The vertex and its normal (world), the guide's mirror and light (centre, radius). */
const POINT: [number, number, number] = [0, 0, 0];
const NORMAL: [number, number, number] = [0.3, 1, 0.2];
const GUIDE = [0.3, 1.6, 0.1, 0.8, -2.5, 3, 1.5, 1.5];

type Vec3 = [number, number, number];
const dot = (a: Vec3, b: Vec3) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];

/** Fraction of the cone's solid angle in each bin (above the horizon only), by a fine equal-area quadrature. */
function coneBinFractions(axis: Vec3, oneMinusCos: number): Float64Array {
  const fractions = new Float64Array(BINS.cosBins * BINS.phiBins);
  const t: Vec3 = Math.abs(axis[2]) < 0.9 ? normalize(cross(axis, [0, 0, 1])) : normalize(cross(axis, [1, 0, 0]));
  const b = cross(axis, t);
  const side = 600;
  for (let i = 0; i < side; i++) {
    const cosTheta = 1 - ((i + 0.5) / side) * oneMinusCos;
    const sinTheta = Math.sqrt(1 - cosTheta * cosTheta);
    for (let j = 0; j < side; j++) {
      const phi = (2 * Math.PI * (j + 0.5)) / side;
      const w = [0, 1, 2].map((k) => axis[k] * cosTheta + sinTheta * (Math.cos(phi) * t[k] + Math.sin(phi) * b[k])) as Vec3;
      if (w[2] > 0) fractions[sphereBin(w[0], w[1], w[2], BINS)] += 1 / (side * side);
    }
  }
  return fractions;
}

function cross(a: Vec3, b: Vec3): Vec3 {
  return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
}
function normalize(a: Vec3): Vec3 {
  const l = Math.hypot(...a);
  return [a[0] / l, a[1] / l, a[2] / l];
}

describe('caustic-guide mixture: sampleGuided agrees with guidedPdf', () => {
  const session = useRenderSession();

  for (const { roughness, theta } of [{ roughness: 1, theta: 30 }, { roughness: 0.5, theta: 60 }]) {
    it(`standard material, roughness ${roughness}, view ${theta} deg`, async () => {
      const t = (theta * Math.PI) / 180;
      const wo: Vec3 = [Math.sin(t), 0, Math.cos(t)];
      const common = { material: { type: 'standard', color: [1, 1, 1], roughness } as Material, wo, point: POINT, normal: NORMAL, guide: GUIDE };
      const setup = await session().runKernel({ ...common, kernel: 'guideSetup', width: 2, height: 1 });
      const axis: Vec3 = [setup[0], setup[1], setup[2]];
      const coneW = setup[3];
      const p = setup[4];
      const setupSummary = JSON.stringify({ axis, coneW, p });
      // The geometry makes a real cone (not the hemisphere fallback), wide
      // enough to span several bins, partly above the horizon.
      expect(coneW, setupSummary).toBeGreaterThan(0.02);
      expect(coneW, setupSummary).toBeLessThan(0.5);
      expect(axis[2], setupSummary).toBeGreaterThan(0);
      expect(p, setupSummary).toBeCloseTo(0.1 * roughness, 6);

      // guidedPdf on the grid = (1 - p) bsdfPdf + p * cone density.
      const width = BINS.phiBins * SUB;
      const height = BINS.cosBins * SUB;
      const grid = await session().runKernel({ ...common, kernel: 'pdfGuided', width, height });
      const conePdf = 1 / (2 * Math.PI * coneW);
      let mismatches = 0;
      let worst = 0;
      for (let gy = 0; gy < height; gy++) {
        for (let gx = 0; gx < width; gx++) {
          const w = gridDirection(gx, gy, width, height);
          const i = (gy * width + gx) * 4;
          const inCone = 1 - dot(w, axis) <= coneW;
          const nearEdge = Math.abs(1 - dot(w, axis) - coneW) < 1e-4; // float rounding decides there
          const expected = (1 - p) * grid[i + 1] + (inCone ? p * conePdf : 0);
          const error = Math.abs(grid[i + 2] - expected) / Math.max(expected, 1e-3);
          if (error > 1e-3 && !nearEdge) mismatches++;
          worst = Math.max(worst, nearEdge ? 0 : error);
        }
      }
      expect(mismatches, `guidedPdf differs from the mixture formula (worst relative ${worst}); ${setupSummary}`).toBe(0);

      // Chi-square of the samples against the mixture.
      const n = SAMPLES_SIDE * SAMPLES_SIDE;
      const samples = await session().runKernel({ ...common, kernel: 'sampleGuided', width: SAMPLES_SIDE, height: SAMPLES_SIDE, seed: 21 });
      const bsdfPart = expectedCounts(grid, 1, BINS, SUB, n);
      const cone = coneBinFractions(axis, coneW);
      const expected = bsdfPart.expected.map((v, i) => (1 - p) * v + p * cone[i] * n);
      const mass = (1 - p) * bsdfPart.mass + p * cone.reduce((s, v) => s + v, 0);
      const observed = new Float64Array(expected.length);
      let valid = 0;
      for (let i = 0; i < n; i++) {
        const [x, y, z, pdf] = samples.subarray(i * 4, i * 4 + 4);
        if (pdf <= 0) continue;
        valid++;
        observed[sphereBin(x, y, z, BINS)]++;
      }
      const result = chiSquareTest(observed, expected);
      const summary = JSON.stringify({ ...result, mass, valid: valid / n, ...JSON.parse(setupSummary) });
      console.log(`guided r ${roughness}: ${summary}`);
      expect(Math.abs(mass - valid / n), summary).toBeLessThan(0.005);
      expect(result.pValue, summary).toBeGreaterThan(ALPHA);

      // Weights: f / mixture pdf per sample; their mean is the albedo.
      const weights = await session().runKernel({ ...common, kernel: 'weightGuided', width: SAMPLES_SIDE, height: SAMPLES_SIDE, seed: 21 });
      let sum = 0;
      let sumSq = 0;
      let worstWeight = 0;
      for (let i = 0; i < n; i++) {
        const [weight, isValid, ratio] = weights.subarray(i * 4, i * 4 + 3);
        if (isValid === 0) continue;
        worstWeight = Math.max(worstWeight, Math.abs(weight - ratio) / Math.max(1e-6, ratio));
        sum += weight;
        sumSq += weight * weight;
      }
      const mean = sum / n;
      const sd = Math.sqrt(sumSq / n - mean * mean);
      const albedo = expectedCounts(grid, 0, BINS, SUB, 1).mass;
      const weightSummary = JSON.stringify({ mean, albedo, sd, worstWeight });
      expect(worstWeight, weightSummary).toBeLessThan(1e-5);
      // 5 sigma of the mean plus 0.3% for the midpoint rule on a smooth f.
      expect(Math.abs(mean - albedo), weightSummary).toBeLessThan((5 * sd) / Math.sqrt(n) + 0.003 * albedo);
    });
  }
});
