import { describe, expect, it } from 'vitest';
import { chiSquareTest, gammaQ } from '../support/chi2';

describe('chi-square test support', () => {
  it('gammaQ matches known chi-square tail values', () => {
    // P(chi2_k > x) = Q(k/2, x/2): critical values at p = 0.05 and 0.01.
    expect(gammaQ(1 / 2, 3.841 / 2)).toBeCloseTo(0.05, 3);
    expect(gammaQ(10 / 2, 23.209 / 2)).toBeCloseTo(0.01, 3);
    expect(gammaQ(100 / 2, 124.342 / 2)).toBeCloseTo(0.05, 3);
  });

  it('accepts a histogram drawn from its pdf and rejects a shifted one', () => {
    let state = 12345;
    const random = () => (state = (Math.imul(state, 1103515245) + 12345) >>> 0) / 2 ** 32;
    const bins = 20;
    const observed = new Float64Array(bins);
    const n = 100_000;
    for (let i = 0; i < n; i++) observed[Math.floor(random() * bins)]++;
    const expected = new Float64Array(bins).fill(n / bins);
    expect(chiSquareTest(observed, expected).pValue).toBeGreaterThan(0.001);
    const skewed = expected.map((e, i) => e * (1 + 0.05 * (i < bins / 2 ? 1 : -1)));
    expect(chiSquareTest(observed, skewed).pValue).toBeLessThan(1e-6);
  });
});
