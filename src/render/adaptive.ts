/**
 * Adaptive sampling (PathTracerOptions.adaptive): samples go where the image
 * is noisy. Pure TypeScript; PathTracer draws what it decides.
 *
 * The image is cut into cells of ADAPTIVE_CELL pixels, a floor grid (every
 * pixel has exactly one cell), drawn as point sprites like tiles.ts's. All
 * pixels of a cell have the same sample count. 8x8 cells did better than
 * 16x16 (bench/adaptive.ts, 3 seeds of 6 s: at equal time against uniform,
 * bunny 0.60 against 0.70, instanced 0.85 against 0.91, bench 1.00 against
 * 1.02): smaller cells follow the noise closer, and 64 pixels x 3 channels
 * still estimate a cell's variance (4x4 cells: bunny 0.70, too rough).
 *
 * A round of `paths` paths is shared among the cells so that each cell's
 * paths are proportional to its pixel count times its standard deviation
 * relative to its brightness: for a relative squared error summed over
 * pixels, that is the allocation of least error for the paths spent
 * (Lagrange: n_c proportional to sigma_c).
 * A fixed share, ADAPTIVE_FLOOR, stays uniform, so no cell starves because
 * its noise was underestimated (a firefly not yet seen).
 *
 * The noise is estimated without storing squares: from the mean image now
 * (n samples per pixel) and an earlier snapshot of it (m < n, the first m of
 * the same samples). Their difference has variance sigma^2 (1/m - 1/n), so
 * (I_n - I_m)^2 / (1/m - 1/n), averaged over the cell's pixels and
 * channels, estimates the variance of one sample. Each term is divided by
 * I_n^2 + ADAPTIVE_EPSILON: dark pixels count by absolute, bright ones by
 * relative error (the benchmark's relMSE weighting).
 *
 * The estimate reads the samples it then allocates by, so a cell's count
 * depends on its own noise: a small bias of the kind every adaptive sampler
 * has (Cycles, V-Ray), shrinking as the rounds double; references pass with it
 * (test/browser/adaptive.test.ts).
 */

/** Side of a cell in pixels (at most the tile size: cells are drawn as point sprites). */
export const ADAPTIVE_CELL = 8;
/** Samples per pixel drawn uniformly before the first snapshot; estimates start once a cell has 1.5 times as many. */
export const ADAPTIVE_START = 4;
/** The share of each round's paths spread uniformly over the pixels. */
export const ADAPTIVE_FLOOR = 0.2;
/** Added to the squared mean in the relative error (as the benchmark's relMSE). */
export const ADAPTIVE_EPSILON = 0.01;
/** A cell gets at most this many times the uniform share of a round. */
export const ADAPTIVE_MAX_RATIO = 16;

/** The cells: a floor grid of `size`-pixel squares over width x height (the last row and column may be partial). */
export interface CellGrid {
  width: number;
  height: number;
  size: number;
  columns: number;
  rows: number;
}

export function cellGrid(width: number, height: number, size: number): CellGrid {
  return { width, height, size, columns: Math.ceil(width / size), rows: Math.ceil(height / size) };
}

/** Pixels in each cell. */
export function cellPixels(grid: CellGrid): Float64Array {
  const pixels = new Float64Array(grid.columns * grid.rows);
  for (let r = 0; r < grid.rows; r++) {
    const h = Math.min(grid.size, grid.height - r * grid.size);
    for (let c = 0; c < grid.columns; c++) pixels[r * grid.columns + c] = h * Math.min(grid.size, grid.width - c * grid.size);
  }
  return pixels;
}

/** Each pixel's count from its cell's (rows as the sums are stored: y from the bottom, like gl_FragCoord). */
export function pixelCounts(grid: CellGrid, cellCounts: ArrayLike<number>): Float64Array {
  const counts = new Float64Array(grid.width * grid.height);
  for (let y = 0; y < grid.height; y++) {
    const row = Math.floor(y / grid.size) * grid.columns;
    for (let x = 0; x < grid.width; x++) counts[y * grid.width + x] = cellCounts[row + Math.floor(x / grid.size)];
  }
  return counts;
}

/** A mean image and the per-cell counts behind it. */
export interface Snapshot {
  /** RGBA sums / count, rows from the bottom. */
  mean: Float32Array;
  counts: Uint32Array;
}

/** The mean of RGBA sums (rows from the bottom) with per-cell counts; 0 where a cell has none. */
export function meanImage(grid: CellGrid, sums: Float32Array, cellCounts: ArrayLike<number>): Float32Array {
  const counts = pixelCounts(grid, cellCounts);
  const mean = new Float32Array(sums.length);
  for (let p = 0; p < counts.length; p++) {
    const scale = counts[p] > 0 ? 1 / counts[p] : 0;
    for (let k = 0; k < 4; k++) mean[p * 4 + k] = sums[p * 4 + k] * scale;
  }
  return mean;
}

/**
 * Per cell, the relative variance of one sample, estimated from the mean
 * now and an earlier snapshot (see above); NaN where a cell has too few new
 * samples since the snapshot to tell (n < 1.5 m, or m = 0).
 */
export function cellVariances(grid: CellGrid, now: Snapshot, before: Snapshot): Float64Array {
  const cells = grid.columns * grid.rows;
  const sum = new Float64Array(cells);
  const terms = new Float64Array(cells);
  for (let y = 0; y < grid.height; y++) {
    for (let x = 0; x < grid.width; x++) {
      const c = Math.floor(y / grid.size) * grid.columns + Math.floor(x / grid.size);
      const p = (y * grid.width + x) * 4;
      for (let k = 0; k < 3; k++) {
        const d = now.mean[p + k] - before.mean[p + k];
        const e = (d * d) / (now.mean[p + k] ** 2 + ADAPTIVE_EPSILON);
        // A non-finite sum (never expected: the shader rejects such samples) counts as very noisy.
        sum[c] += Number.isFinite(e) ? e : 1e30;
        terms[c] += 1;
      }
    }
  }
  const variance = new Float64Array(cells);
  for (let c = 0; c < cells; c++) {
    const n = now.counts[c];
    const m = before.counts[c];
    variance[c] = m > 0 && n >= 1.5 * m ? sum[c] / terms[c] / (1 / m - 1 / n) : NaN;
  }
  return variance;
}

/**
 * Samples per pixel for each cell for a round of `paths` paths: the floor
 * share uniform, the rest by pixels x relative standard deviation. Cells
 * without an estimate (NaN) take the mean deviation of those with one.
 * `carry` (one per cell, kept across rounds) holds the fractions of a sample
 * not yet drawn, so the counts are whole and the paths add up over rounds.
 */
export function allocate(grid: CellGrid, variances: ArrayLike<number>, paths: number, carry: Float64Array): Uint32Array {
  const pixels = cellPixels(grid);
  const cells = pixels.length;
  const totalPixels = grid.width * grid.height;
  const deviations = Array.from(variances, (v) => (Number.isFinite(v) && v >= 0 ? Math.sqrt(v) : NaN));
  const known = deviations.filter((d) => !Number.isNaN(d));
  const fallback = known.length > 0 ? known.reduce((a, b) => a + b, 0) / known.length : 1;
  let weightSum = 0;
  const weights = new Float64Array(cells);
  for (let c = 0; c < cells; c++) {
    const d = Number.isNaN(deviations[c]) ? fallback : deviations[c];
    weights[c] = pixels[c] * d;
    weightSum += weights[c];
  }
  const uniform = paths / totalPixels;
  const perPixel = new Float64Array(cells);
  for (let c = 0; c < cells; c++) {
    const adaptive = weightSum > 0 ? (paths * weights[c]) / weightSum / pixels[c] : uniform;
    perPixel[c] = ADAPTIVE_FLOOR * uniform + (1 - ADAPTIVE_FLOOR) * adaptive;
  }
  capAndRefill(perPixel, pixels, ADAPTIVE_MAX_RATIO * uniform);
  const samples = new Uint32Array(cells);
  for (let c = 0; c < cells; c++) {
    carry[c] += perPixel[c];
    samples[c] = Math.floor(carry[c] + 1e-9);
    carry[c] -= samples[c];
  }
  return samples;
}

/** Caps each cell's samples per pixel at `cap` and gives what the capped cells lose to the others, in proportion (water-filling). */
function capAndRefill(perPixel: Float64Array, pixels: Float64Array, cap: number): void {
  for (let pass = 0; pass < 8; pass++) {
    let excess = 0;
    let open = 0;
    for (let c = 0; c < perPixel.length; c++) {
      if (perPixel[c] > cap) {
        excess += (perPixel[c] - cap) * pixels[c];
        perPixel[c] = cap;
      } else if (perPixel[c] < cap) {
        open += perPixel[c] * pixels[c];
      }
    }
    if (excess <= 0 || open <= 0) return;
    const scale = 1 + excess / open;
    for (let c = 0; c < perPixel.length; c++) if (perPixel[c] < cap) perPixel[c] *= scale;
  }
}

/**
 * The state of an adaptive accumulation: each cell's count, the snapshot
 * the noise is measured against, the latest estimates and the carried
 * fractions. PathTracer reads the sums and draws what `plan` returns.
 */
export class AdaptiveCells {
  readonly counts: Uint32Array;
  private readonly carry: Float64Array;
  private readonly variances: Float64Array;
  private snapshot: Snapshot | null = null;

  /** Starts from `uniformCount` samples in every pixel. */
  constructor(
    readonly grid: CellGrid,
    uniformCount: number,
  ) {
    const cells = grid.columns * grid.rows;
    this.counts = new Uint32Array(cells).fill(uniformCount);
    this.carry = new Float64Array(cells);
    this.variances = new Float64Array(cells).fill(NaN);
  }

  /** Remembers the mean of `sums` (rows from the bottom) as the image the next estimates compare with. */
  takeSnapshot(sums: Float32Array): void {
    this.snapshot = { mean: meanImage(this.grid, sums, this.counts), counts: this.counts.slice() };
  }

  /**
   * Samples per pixel for each cell for a round of about `paths` paths,
   * given the sums now: updates the noise estimates (keeping a cell's last
   * one where it cannot tell yet), and moves the snapshot here once every
   * cell has at least doubled since it.
   */
  plan(sums: Float32Array, paths: number): Uint32Array {
    const now: Snapshot = { mean: meanImage(this.grid, sums, this.counts), counts: this.counts.slice() };
    const before = this.snapshot ?? now;
    cellVariances(this.grid, now, before).forEach((v, c) => {
      if (!Number.isNaN(v)) this.variances[c] = v;
    });
    if (!this.snapshot || this.counts.every((n, c) => n >= 2 * before.counts[c])) this.snapshot = now;
    return allocate(this.grid, this.variances, paths, this.carry);
  }

  /** Adds drawn samples per cell. */
  add(samples: Uint32Array): void {
    samples.forEach((n, c) => (this.counts[c] += n));
  }

  /** Paths behind the sums: each cell's count times its pixels. */
  get paths(): number {
    const pixels = cellPixels(this.grid);
    return this.counts.reduce((sum, n, c) => sum + n * pixels[c], 0);
  }
}
