import type { Material } from '../../src/scene/types';
/**
 * The shader's samplers against their pdfs, in the browser (the GLSL code
 * itself, through src/headless/kernels.ts): a chi-square test of a 2D
 * histogram over (cos theta, phi) against the counts that integrating the
 * pdf predicts, as Mitsuba 3 tests its BSDFs and emitters.
 */
import { describe, expect, it } from 'vitest';
import { chiSquareTest } from '../support/chi2';
import { useRenderSession } from '../support/browser';

const SAMPLES_SIDE = 512; // 262,144 samples per test
/** Significance of each test; with ~10 tests the false-failure rate stays below 1e-3. */
const ALPHA = 1e-4;

describe('samplers agree with their pdfs', () => {
  const session = useRenderSession();

  for (const oneMinusCosMax of [0.5, 0.02, 1e-4]) {
    it(`light cone sampler, 1 - cos(theta_max) = ${oneMinusCosMax}`, async () => {
      const data = await session().runKernel({
        kernel: 'sampleCone', width: SAMPLES_SIDE, height: SAMPLES_SIDE, params: [oneMinusCosMax], seed: 3,
      });
      const cosBins = 10;
      const phiBins = 20;
      const observed = new Float64Array(cosBins * phiBins);
      const expectedPdf = 1 / (2 * Math.PI * oneMinusCosMax);
      const n = SAMPLES_SIDE * SAMPLES_SIDE;
      let worstNorm = 0;
      let worstPdf = 0;
      let outsideCone = 0;
      for (let i = 0; i < n; i++) {
        const [x, y, z, pdf] = data.subarray(i * 4, i * 4 + 4);
        worstNorm = Math.max(worstNorm, Math.abs(Math.hypot(x, y, z) - 1));
        worstPdf = Math.max(worstPdf, Math.abs(pdf / expectedPdf - 1));
        if (1 - z > oneMinusCosMax * (1 + 1e-3) + 1e-6) outsideCone++;
        // Uniform in solid angle inside the cone = uniform in (cos theta, phi).
        const u = Math.min(cosBins - 1, Math.max(0, Math.floor(((1 - z) / oneMinusCosMax) * cosBins)));
        const v = Math.min(phiBins - 1, Math.floor(((Math.atan2(y, x) + 2 * Math.PI) % (2 * Math.PI)) / (2 * Math.PI) * phiBins));
        observed[u * phiBins + v]++;
      }
      // SwiftShader's sin/cos are approximations good to ~1e-4.
      expect(worstNorm).toBeLessThan(1e-3);
      expect(worstPdf).toBeLessThan(1e-4);
      expect(outsideCone).toBe(0);
      const expected = new Float64Array(cosBins * phiBins).fill(n / (cosBins * phiBins));
      const result = chiSquareTest(observed, expected);
      expect(result.pValue, JSON.stringify(result)).toBeGreaterThan(ALPHA);
    });
  }

  const cases: { roughness: number; theta: number }[] = [
    { roughness: 1, theta: 30 },
    { roughness: 0.6, theta: 10 },
    { roughness: 0.6, theta: 70 },
    { roughness: 0.35, theta: 45 },
  ];
  for (const { roughness, theta } of cases) {
    it(`material sampler (GGX visible normals + Lambert), roughness ${roughness}, view ${theta} deg`, async () => {
      const t = (theta * Math.PI) / 180;
      const wo: [number, number, number] = [Math.sin(t), 0, Math.cos(t)];
      const cosBins = 20;
      const phiBins = 40;
      const sub = 16; // pdf evaluations per bin side for the expected counts
      const samples = await session().runKernel({
        kernel: 'sampleMaterial', width: SAMPLES_SIDE, height: SAMPLES_SIDE, material: { type: 'standard', color: [1, 1, 1], roughness } as Material, wo, seed: 5,
      });
      const pdfGrid = await session().runKernel({
        kernel: 'pdfMaterial', width: phiBins * sub, height: cosBins * sub, material: { type: 'standard', color: [1, 1, 1], roughness } as Material, wo,
      });

      // Expected counts: the pdf integrated over each bin (midpoint rule on
      // the kernel's grid, uniform in cos theta and phi, so dA = dcos dphi).
      const n = SAMPLES_SIDE * SAMPLES_SIDE;
      const cell = (2 / (cosBins * sub)) * ((2 * Math.PI) / (phiBins * sub));
      const expected = new Float64Array(cosBins * phiBins);
      let total = 0;
      for (let gy = 0; gy < cosBins * sub; gy++) {
        for (let gx = 0; gx < phiBins * sub; gx++) {
          const pdf = pdfGrid[(gy * phiBins * sub + gx) * 4 + 3];
          expected[Math.floor(gy / sub) * phiBins + Math.floor(gx / sub)] += pdf * cell * n;
          total += pdf * cell;
        }
      }
      const observed = new Float64Array(cosBins * phiBins);
      let valid = 0;
      let belowHorizon = 0;
      for (let i = 0; i < n; i++) {
        const [x, y, z, pdf] = samples.subarray(i * 4, i * 4 + 4);
        if (pdf === 0) continue; // invalid sample (below the horizon): the pdf has no mass there either
        if (z <= 0) belowHorizon++;
        valid++;
        const u = Math.min(cosBins - 1, Math.floor(((z + 1) / 2) * cosBins));
        const v = Math.min(phiBins - 1, Math.floor(((Math.atan2(y, x) + 2 * Math.PI) % (2 * Math.PI)) / (2 * Math.PI) * phiBins));
        observed[u * phiBins + v]++;
      }
      // The pdf's mass equals the fraction of valid samples (VNDF sampling may
      // leave the hemisphere; those samples are discarded by the integrator).
      const result = chiSquareTest(observed, expected);
      expect(belowHorizon).toBe(0);
      expect(valid / n, 'most samples must be valid').toBeGreaterThan(0.5);
      expect(Math.abs(total - valid / n)).toBeLessThan(0.01);
      expect(result.degreesOfFreedom).toBeGreaterThan(20);
      expect(result.pValue, JSON.stringify({ ...result, total, valid: valid / n })).toBeGreaterThan(ALPHA);
    });
  }
});
