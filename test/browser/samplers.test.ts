/**
 * The light cone sampler against its pdf, in the browser (the GLSL code
 * itself, through src/headless/kernels.ts): a chi-square test of a 2D
 * histogram over (cos theta, phi) against the counts that integrating the
 * pdf predicts, as Mitsuba 3 tests its emitters. The materials' samplers
 * are tested beside each kind (src/materials/<kind>/<kind>.test.ts).
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
});
