/**
 * The environment map's sampling distribution: CDFs and alias tables are
 * consistent, the solid-angle pdf integrates to 1 over the sphere, the
 * TypeScript reference sampler draws exactly from that pdf (chi-square), and
 * the density follows the map's bilinear radiance.
 */
import { describe, expect, it } from 'vitest';
import {
  buildEnvironmentDistribution,
  environmentDistributionPdf,
  environmentDistributionPdfUv,
  sampleEnvironmentDistribution,
  type EnvironmentDistribution,
} from '../../src/scene/envmap/distribution';
import { directionToUv, lookupEnvironment, uvToDirection } from '../../src/scene/envmap/mapping';
import type { EnvironmentImage } from '../../src/scene/types';
import { chiSquareTest } from '../support/chi2';
import { random as mulberry32 } from '../support/random';

const ALPHA = 1e-4;


function makeImage(width: number, height: number, f: (x: number, y: number) => number): EnvironmentImage {
  const rgb = new Float32Array(width * height * 3);
  for (let y = 0; y < height; y++) for (let x = 0; x < width; x++) rgb.fill(f(x, y), (y * width + x) * 3, (y * width + x) * 3 + 3);
  return { width, height, rgb };
}

const smooth = makeImage(32, 17, (x, y) => 1 + Math.sin(x / 3) ** 2 * 4 + y / 4);
const spot = makeImage(40, 21, (x, y) => (x === 29 && y === 6 ? 5000 : 0.01));
const random = (() => {
  const rand = mulberry32(7);
  return makeImage(23, 12, () => (rand() < 0.3 ? 0 : rand() ** 4 * 100));
})();
const MAPS: [string, EnvironmentImage][] = [['smooth', smooth], ['tiny bright spot', spot], ['random with black texels', random]];

/** Probability that the alias table at `offset` draws each of its `n` entries. */
function aliasDrawProbabilities(table: Float32Array, offset: number, n: number): Float64Array {
  const p = new Float64Array(n);
  for (let i = 0; i < n; i++) {
    const keep = table[offset + i * 4];
    p[i] += keep / n;
    p[table[offset + i * 4 + 1]] += (1 - keep) / n;
  }
  return p;
}

function checkTable(table: Float32Array, offset: number, n: number): void {
  let cdf = 0;
  const drawn = aliasDrawProbabilities(table, offset, n);
  for (let i = 0; i < n; i++) {
    const [keep, alias, probability, aliasProbability] = table.subarray(offset + i * 4, offset + i * 4 + 4);
    expect(keep).toBeGreaterThanOrEqual(0);
    expect(keep).toBeLessThanOrEqual(1);
    expect(Number.isInteger(alias) && alias >= 0 && alias < n).toBe(true);
    expect(aliasProbability).toBe(table[offset + alias * 4 + 2]);
    expect(probability).toBeGreaterThanOrEqual(0);
    cdf += probability; // the CDF: monotone because no probability is negative
    expect(Math.abs(drawn[i] - probability)).toBeLessThanOrEqual(1e-6 * probability + 1e-12);
  }
  expect(Math.abs(cdf - 1)).toBeLessThan(1e-5);
}

describe('environment distribution tables', () => {
  for (const [name, image] of MAPS) {
    it(`${name}: probabilities sum to 1; the alias tables draw exactly the stored probabilities`, () => {
      const d = buildEnvironmentDistribution(image);
      expect([d.width, d.rows]).toEqual([image.width, image.height - 1]);
      checkTable(d.marginal, 0, d.rows);
      for (let j = 0; j < d.rows; j++) checkTable(d.conditional, j * d.width * 4, d.width);
    });

    it(`${name}: the solid-angle pdf integrates to 1 over the sphere`, () => {
      const d = buildEnvironmentDistribution(image);
      // Midpoint rule, uniform in (cos theta, phi): dA = 4 pi / N.
      const nz = 1500;
      const nphi = 1500;
      let sum = 0;
      for (let a = 0; a < nz; a++) {
        const z = 1 - (2 * (a + 0.5)) / nz;
        const s = Math.sqrt(1 - z * z);
        for (let b = 0; b < nphi; b++) {
          const phi = (2 * Math.PI * (b + 0.5)) / nphi;
          const { u, v } = directionToUv([s * Math.cos(phi), z, s * Math.sin(phi)], 33);
          sum += environmentDistributionPdf(d, u, v);
        }
      }
      expect(Math.abs((sum * 4 * Math.PI) / (nz * nphi) - 1)).toBeLessThan(5e-3);
    });
  }

  it('a black map gets a uniform distribution over the sphere and integral 0', () => {
    const d = buildEnvironmentDistribution(makeImage(8, 5, () => 0));
    expect(d.integral).toBe(0);
    for (const v of [0.1, 0.3, 0.5, 0.8]) expect(environmentDistributionPdf(d, 0.37, v)).toBeCloseTo(1 / (4 * Math.PI), 1);
  });

  it('the integral of a constant map is 4 pi times its value', () => {
    expect(buildEnvironmentDistribution(makeImage(16, 9, () => 2)).integral).toBeCloseTo(8 * Math.PI, 10);
    expect(buildEnvironmentDistribution(makeImage(1, 1, () => 2)).integral).toBeCloseTo(8 * Math.PI, 10);
  });

  it('the density is zero exactly where the bilinear radiance is zero over the cell, and follows it elsewhere', () => {
    const d = buildEnvironmentDistribution(makeImage(40, 21, (x, y) => (x === 29 && y === 6 ? 1 : 0)));
    // The texel's bilinear support: u within one column of (29.5) / 40, v within one row of 6 / 20.
    for (let k = 0; k < 2000; k++) {
      const u = (k % 50) / 50 + 0.003;
      const v = Math.floor(k / 50) / 40 + 0.004;
      const radiance = lookupEnvironment(makeImage(40, 21, (x, y) => (x === 29 && y === 6 ? 1 : 0)), u, v)[0];
      const inSupport = Math.abs(u - 29.5 / 40) < 1 / 40 && Math.abs(v - 6 / 20) < 1 / 20;
      expect(environmentDistributionPdfUv(d, u, v) > 0).toBe(inSupport);
      if (radiance > 0) expect(inSupport).toBe(true);
    }
  });
});

function overlap(a0: number, a1: number, b0: number, b1: number): number {
  return Math.max(0, Math.min(a1, b1) - Math.max(a0, b0));
}

/** Chi-square of the reference sampler against its own pdf on a grid of (u, v) bins that do not align with the cells. */
function chiSquareUv(d: EnvironmentDistribution, seed: number): ReturnType<typeof chiSquareTest> {
  const bins = { u: 37, v: 19 };
  const n = 300_000;
  const rand = mulberry32(seed);
  const observed = new Float64Array(bins.u * bins.v);
  let worstPdf = 0;
  for (let i = 0; i < n; i++) {
    const s = sampleEnvironmentDistribution(d, rand(), rand());
    worstPdf = Math.max(worstPdf, Math.abs(s.pdfUv / environmentDistributionPdfUv(d, s.u, s.v) - 1));
    observed[Math.min(Math.floor(s.v * bins.v), bins.v - 1) * bins.u + Math.min(Math.floor(s.u * bins.u), bins.u - 1)]++;
  }
  // Expected counts: the mass of each cell spread over the bins it overlaps (exact for a piecewise-constant pdf).
  const expected = new Float64Array(bins.u * bins.v);
  for (let j = 0; j < d.rows; j++) {
    for (let i = 0; i < d.width; i++) {
      const mass = d.marginal[j * 4 + 2] * d.conditional[(j * d.width + i) * 4 + 2] * n;
      if (mass === 0) continue;
      for (let by = 0; by < bins.v; by++) {
        const fy = overlap(by / bins.v, (by + 1) / bins.v, j / d.rows, (j + 1) / d.rows) * d.rows;
        if (fy === 0) continue;
        for (let bx = 0; bx < bins.u; bx++) {
          const lo = (i + 0.5) / d.width;
          const hi = (i + 1.5) / d.width; // may pass 1: the part beyond wraps to the start
          const ux = overlap(bx / bins.u, (bx + 1) / bins.u, lo, hi) + overlap(bx / bins.u, (bx + 1) / bins.u, lo - 1, hi - 1);
          expected[by * bins.u + bx] += mass * fy * ux * d.width;
        }
      }
    }
  }
  expect(worstPdf, 'the pdf returned with a sample is the pdf at its point').toBeLessThan(1e-6);
  return chiSquareTest(observed, expected);
}

describe('the reference sampler draws from its pdf', () => {
  MAPS.forEach(([name, image], k) => {
    it(`${name}: chi-square over (u, v)`, () => {
      const result = chiSquareUv(buildEnvironmentDistribution(image), 11 + k);
      expect(result.degreesOfFreedom).toBeGreaterThan(name === 'tiny bright spot' ? 2 : 100);
      expect(result.pValue, JSON.stringify(result)).toBeGreaterThan(ALPHA);
    });
  });

  it('a sampler that ignores the sin theta weighting fails the test (the test can fail)', () => {
    const d = buildEnvironmentDistribution(smooth);
    // Rows drawn uniformly: every row keeps itself.
    const sampled = { ...d, marginal: d.marginal.slice() };
    for (let j = 0; j < d.rows; j++) sampled.marginal.set([1, j], j * 4);
    // Sample with the wrong tables, evaluate the right pdf.
    const rand = mulberry32(5);
    const bins = 10;
    const observed = new Float64Array(bins);
    const expected = new Float64Array(bins);
    const n = 100_000;
    for (let i = 0; i < n; i++) observed[Math.min(Math.floor(sampleEnvironmentDistribution(sampled, rand(), rand()).v * bins), bins - 1)]++;
    for (let k = 0; k < 1000; k++) expected[Math.floor(k / 100)] += (environmentDistributionPdfUv(d, 0.5, (k + 0.5) / 1000) * n) / 1000;
    expect(chiSquareTest(observed, expected).pValue).toBeLessThan(1e-6);
  });

  it('sampled directions map back to the sampled (u, v) with any rotation', () => {
    const rand = mulberry32(3);
    for (let i = 0; i < 1000; i++) {
      const u = rand();
      const v = 0.01 + 0.98 * rand();
      const rotation = 360 * rand() - 180;
      const back = directionToUv(uvToDirection(u, v, rotation), rotation);
      expect(Math.min(Math.abs(back.u - u), 1 - Math.abs(back.u - u))).toBeLessThan(1e-9);
      expect(back.v).toBeCloseTo(v, 9);
    }
  });
});

describe('compensated distribution (pbrt-v4: max(L - average, 0))', () => {
  const d = buildEnvironmentDistribution(smooth, { compensated: true });

  it('tables are consistent and the sampler draws from its pdf', () => {
    checkTable(d.marginal, 0, d.rows);
    for (let j = 0; j < d.rows; j++) checkTable(d.conditional, j * d.width * 4, d.width);
    const result = chiSquareUv(d, 99);
    expect(result.pValue, JSON.stringify(result)).toBeGreaterThan(ALPHA);
  });

  it('puts no density where the map is below its average, some where it is above; the integral is the map\'s', () => {
    // Smoother than `smooth`: under 5 % change from one texel to the next.
    const gentle = makeImage(64, 33, (x, y) => 1 + 2 * Math.sin((Math.PI * x) / 64) ** 2 + y / 32);
    const d = buildEnvironmentDistribution(gentle, { compensated: true });
    const plain = buildEnvironmentDistribution(gentle);
    expect(d.integral).toBe(plain.integral);
    const average = plain.integral / (4 * Math.PI); // the map's mean luminance over the sphere
    let zero = 0;
    let positive = 0;
    for (let k = 0; k < 4000; k++) {
      const u = (k % 80) / 80 + 0.004;
      const v = Math.floor(k / 80) / 50 + 0.005;
      const [r, g, b] = lookupEnvironment(gentle, u, v);
      const luminance = 0.2126 * r + 0.7152 * g + 0.0722 * b;
      const pdf = environmentDistributionPdfUv(d, u, v);
      // Cells are at most one texel across and the map is smooth: 10 % margins.
      if (luminance < average * 0.9) { expect(pdf).toBe(0); zero++; }
      if (luminance > average * 1.1) { expect(pdf).toBeGreaterThan(0); positive++; }
    }
    expect(zero).toBeGreaterThan(500);
    expect(positive).toBeGreaterThan(500);
  });

  it('a constant map falls back to the plain distribution', () => {
    const constant = makeImage(16, 9, () => 3);
    expect(buildEnvironmentDistribution(constant, { compensated: true })).toEqual(buildEnvironmentDistribution(constant));
  });
});
