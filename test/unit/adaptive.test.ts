/**
 * Adaptive sampling's decisions (src/render/adaptive.ts), without a GPU: the
 * cells, the noise estimate from a snapshot, the allocation, and a whole
 * accumulation simulated with Gaussian samples whose noise sits in a few
 * cells, which must end with less error than uniform sampling for the same
 * paths and the same mean.
 */
import { describe, expect, it } from 'vitest';
import {
  ADAPTIVE_FLOOR,
  ADAPTIVE_MAX_RATIO,
  ADAPTIVE_START,
  AdaptiveCells,
  allocate,
  cellGrid,
  cellPixels,
  cellVariances,
  meanImage,
  pixelCounts,
} from '../../src/render/adaptive';

/** Deterministic standard normals (mulberry32 + Box-Muller). */
function normals(seed: number): () => number {
  let a = seed >>> 0;
  const uniform = () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
  return () => Math.sqrt(-2 * Math.log(1 - uniform())) * Math.cos(2 * Math.PI * uniform());
}

/** A picture whose pixels have mean 0.5 and per-sample deviation sigma(cell). */
class Simulated {
  readonly sums: Float32Array;
  constructor(
    readonly grid: ReturnType<typeof cellGrid>,
    readonly sigma: (cell: number) => number,
    readonly next: () => number,
  ) {
    this.sums = new Float32Array(grid.width * grid.height * 4);
  }
  /** Adds samples[c] samples to every pixel of cell c. */
  add(samples: ArrayLike<number>): void {
    const { grid } = this;
    for (let y = 0; y < grid.height; y++) {
      for (let x = 0; x < grid.width; x++) {
        const c = Math.floor(y / grid.size) * grid.columns + Math.floor(x / grid.size);
        for (let s = 0; s < samples[c]; s++) {
          const v = 0.5 + this.sigma(c) * this.next();
          for (let k = 0; k < 3; k++) this.sums[(y * grid.width + x) * 4 + k] += v;
        }
      }
    }
  }
  relMse(counts: ArrayLike<number>): number {
    const mean = meanImage(this.grid, this.sums, counts);
    let e = 0;
    for (let p = 0; p < this.grid.width * this.grid.height; p++) e += (mean[p * 4] - 0.5) ** 2 / (0.25 + 0.01);
    return e / (this.grid.width * this.grid.height);
  }
}

describe('adaptive sampling: cells', () => {
  it('cover every pixel once, partial cells at the right and top', () => {
    const grid = cellGrid(37, 20, 16);
    expect([grid.columns, grid.rows]).toEqual([3, 2]);
    const pixels = cellPixels(grid);
    expect(Array.from(pixels)).toEqual([256, 256, 80, 64, 64, 20]);
    expect(pixels.reduce((a, b) => a + b, 0)).toBe(37 * 20);
    const counts = pixelCounts(grid, [1, 2, 3, 4, 5, 6]);
    expect(counts[0]).toBe(1);
    expect(counts[36]).toBe(3);
    expect(counts[19 * 37 + 36]).toBe(6);
  });
});

describe('adaptive sampling: the noise estimate', () => {
  it('recovers each cell per-sample relative variance from a snapshot and the mean now', () => {
    const grid = cellGrid(64, 32, 16);
    const sigmas = [0.05, 0.1, 0.2, 0.4, 0.05, 0.1, 0.2, 0.4];
    const sim = new Simulated(grid, (c) => sigmas[c], normals(7));
    const counts = new Uint32Array(8).fill(8);
    sim.add(counts);
    const before = { mean: meanImage(grid, sim.sums, counts), counts: counts.slice() };
    const more = new Uint32Array(8).fill(24);
    sim.add(more);
    more.forEach((n, c) => (counts[c] += n));
    const now = { mean: meanImage(grid, sim.sums, counts), counts };
    const v = cellVariances(grid, now, before);
    sigmas.forEach((s, c) => {
      const expected = (s * s) / (0.25 + 0.01);
      // 256 pixels x 3 (equal) channels: 256 independent terms, about 9% standard error.
      expect(v[c] / expected).toBeGreaterThan(0.7);
      expect(v[c] / expected).toBeLessThan(1.3);
    });
  });

  it('gives no estimate where a cell has not grown by half since the snapshot', () => {
    const grid = cellGrid(16, 16, 16);
    const mean = new Float32Array(16 * 16 * 4).fill(0.5);
    expect(cellVariances(grid, { mean, counts: Uint32Array.of(10) }, { mean, counts: Uint32Array.of(8) })[0]).toBeNaN();
    expect(cellVariances(grid, { mean, counts: Uint32Array.of(12) }, { mean, counts: Uint32Array.of(0) })[0]).toBeNaN();
    expect(cellVariances(grid, { mean, counts: Uint32Array.of(12) }, { mean, counts: Uint32Array.of(8) })[0]).toBe(0);
  });
});

describe('adaptive sampling: the allocation', () => {
  const grid = cellGrid(64, 32, 16); // 8 full cells of 256 pixels

  it('spends the round\'s paths, the floor share uniformly and the rest by deviation', () => {
    const carry = new Float64Array(8);
    const variances = [1, 1, 1, 1, 1, 1, 4, 16]; // deviations 1, 1, 1, 1, 1, 1, 2, 4
    const paths = 64 * 32 * 100;
    const samples = allocate(grid, variances, paths, carry);
    const spent = samples.reduce((a, n) => a + n * 256, 0);
    expect(Math.abs(spent - paths)).toBeLessThanOrEqual(8 * 256);
    // 100 spp uniform: floor 20 each, the other 80 x 8 cells shared 1:1:1:1:1:1:2:4 (sum 12).
    const expected = (d: number) => ADAPTIVE_FLOOR * 100 + (1 - ADAPTIVE_FLOOR) * 800 * (d / 12);
    expect(samples[0]).toBeCloseTo(expected(1), -0.5);
    expect(samples[6]).toBeCloseTo(expected(2), -0.5);
    expect(samples[7]).toBeCloseTo(expected(4), -0.5);
  });

  it('gives a noiseless cell (a plain sky) only the floor', () => {
    const samples = allocate(grid, [1, 1, 1, 1, 1, 1, 1, 0], 64 * 32 * 100, new Float64Array(8));
    expect(samples[7]).toBeCloseTo(ADAPTIVE_FLOOR * 100, -0.5);
  });

    it('caps a cell at ADAPTIVE_MAX_RATIO times uniform and gives the rest to the others', () => {
    const carry = new Float64Array(8);
    const samples = allocate(grid, [1e-8, 1e-8, 1e-8, 1e-8, 1e-8, 1e-8, 1e-8, 1e6], 64 * 32 * 10, carry);
    expect(samples[7]).toBeLessThanOrEqual(ADAPTIVE_MAX_RATIO * 10);
    expect(samples.reduce((a, n) => a + n * 256, 0)).toBeGreaterThan(64 * 32 * 10 - 8 * 256);
  });

  it('gives cells without an estimate the mean deviation, and whole samples that add up over rounds', () => {
    const carry = new Float64Array(8);
    let total = 0;
    for (let round = 0; round < 10; round++) {
      const samples = allocate(grid, [NaN, 1, 1, 1, 1, 1, 1, 1], 64 * 32 * 0.3, carry);
      total += samples.reduce((a, n) => a + n, 0);
    }
    // 0.3 spp a round for 10 rounds: 3 per cell, 24 in all (the fractions carry over).
    expect(total).toBe(24);
  });
});

describe('adaptive sampling: a whole accumulation (simulated)', () => {
  it('ends with less error than uniform sampling for the same paths when the noise is in a few cells', () => {
    const grid = cellGrid(96, 64, 16); // 24 cells
    const sigma = (c: number) => (c === 5 || c === 17 ? 2 : 0.1);
    const uniform = new Simulated(grid, sigma, normals(1));
    const adaptive = new Simulated(grid, sigma, normals(2));
    const cells = new AdaptiveCells(grid, ADAPTIVE_START);
    const start = new Uint32Array(24).fill(ADAPTIVE_START);
    uniform.add(start);
    adaptive.add(start);
    cells.takeSnapshot(adaptive.sums);
    let spp = ADAPTIVE_START;
    for (const round of [4, 8, 16, 32]) {
      const samples = cells.plan(adaptive.sums, round * 96 * 64);
      adaptive.add(samples);
      cells.add(samples);
      uniform.add(new Uint32Array(24).fill(round));
      spp += round;
    }
    const uniformCounts = new Uint32Array(24).fill(spp);
    expect(Math.abs(cells.paths - spp * 96 * 64) / (spp * 96 * 64)).toBeLessThan(0.02);
    // Optimal allocation gains (mean sigma^2) / (mean sigma)^2 = 5.4x here; the floor and the early uniform rounds keep part of it.
    const ratio = adaptive.relMse(cells.counts) / uniform.relMse(uniformCounts);
    console.log(`simulated adaptive / uniform relMSE: ${ratio.toFixed(3)}`);
    expect(ratio).toBeLessThan(0.5);
    // The noisy cells got the most samples, the quiet ones at least the floor.
    expect(cells.counts[5]).toBeGreaterThan(3 * spp);
    expect(Math.min(...cells.counts)).toBeGreaterThanOrEqual(Math.floor(ADAPTIVE_FLOOR * (spp - ADAPTIVE_START)));
  });
});
