/**
 * Error measures between a rendered linear image and a reference, shared by
 * the tests and the benchmark. Images are RGB or RGBA float32, rows top to
 * bottom, with the channel count given.
 */

export interface LinearImage {
  width: number;
  height: number;
  channels: number;
  data: Float32Array;
}

/** The benchmark's relMSE: mean over pixels and channels of (x - ref)^2 / (ref^2 + 0.01). */
export function relativeMse(image: LinearImage, reference: LinearImage): number {
  checkSameSize(image, reference);
  let sum = 0;
  for (let p = 0; p < image.width * image.height; p++) {
    for (let c = 0; c < 3; c++) {
      const x = image.data[p * image.channels + c];
      const r = reference.data[p * reference.channels + c];
      sum += ((x - r) * (x - r)) / (r * r + 0.01);
    }
  }
  return sum / (image.width * image.height * 3);
}

/**
 * Mean of each of the first `colors` channels (3, or 1 for a grey image)
 * over each block x block tile, `colors` values per block, row-major
 * (partial tiles at the edges are dropped).
 */
export function blockMeans(image: LinearImage, block: number, colors = 3): { cols: number; rows: number; means: Float64Array } {
  const cols = Math.floor(image.width / block);
  const rows = Math.floor(image.height / block);
  const means = new Float64Array(cols * rows * colors);
  for (let by = 0; by < rows; by++) {
    for (let bx = 0; bx < cols; bx++) {
      for (let y = by * block; y < (by + 1) * block; y++) {
        for (let x = bx * block; x < (bx + 1) * block; x++) {
          const p = (y * image.width + x) * image.channels;
          for (let c = 0; c < colors; c++) means[(by * cols + bx) * colors + c] += image.data[p + c];
        }
      }
    }
  }
  return { cols, rows, means: means.map((v) => v / (block * block)) };
}

export function meanValue(image: LinearImage): number {
  let sum = 0;
  for (let p = 0; p < image.width * image.height; p++) {
    for (let c = 0; c < 3; c++) sum += image.data[p * image.channels + c];
  }
  return sum / (image.width * image.height * 3);
}

export interface BlockComparison {
  /** Largest |a - b| / (b + floor) over blocks and channels. */
  worst: number;
  worstBlock: { x: number; y: number; channel: number; actual: number; expected: number };
  /** The same relative error for every block (max over channels), row-major. */
  errors: Float64Array;
  cols: number;
  rows: number;
}

/**
 * Relative error of block means. `floor` keeps near-black blocks from
 * dominating: an absolute error of `floor` counts as 100% there.
 */
export function compareBlocks(image: LinearImage, reference: LinearImage, block: number, floor: number): BlockComparison {
  checkSameSize(image, reference);
  const a = blockMeans(image, block);
  const b = blockMeans(reference, block);
  const errors = new Float64Array(a.cols * a.rows);
  let worst = -1;
  let worstBlock = { x: 0, y: 0, channel: 0, actual: 0, expected: 0 };
  for (let i = 0; i < errors.length; i++) {
    for (let c = 0; c < 3; c++) {
      const actual = a.means[i * 3 + c];
      const expected = b.means[i * 3 + c];
      const error = Math.abs(actual - expected) / (expected + floor);
      errors[i] = Math.max(errors[i], error);
      if (error > worst) {
        worst = error;
        worstBlock = { x: i % a.cols, y: Math.floor(i / a.cols), channel: c, actual, expected };
      }
    }
  }
  return { worst, worstBlock, errors, cols: a.cols, rows: a.rows };
}

function checkSameSize(a: LinearImage, b: LinearImage): void {
  if (a.width !== b.width || a.height !== b.height) {
    throw new Error(`image sizes differ: ${a.width}x${a.height} vs ${b.width}x${b.height}`);
  }
}

/** The per-pixel mean of independent renders (batches) of one image. */
export function average(images: LinearImage[]): LinearImage {
  const data = new Float32Array(images[0].data.length);
  for (const image of images) image.data.forEach((v, i) => (data[i] += v / images.length));
  return { ...images[0], data };
}

/** Per-pixel variance of the average of the batches: their sample variance / their count. */
export function varianceOfMean(images: LinearImage[], mean: LinearImage): LinearImage {
  const k = images.length;
  const data = new Float32Array(mean.data.length);
  for (const image of images) image.data.forEach((v, i) => (data[i] += (v - mean.data[i]) ** 2 / ((k - 1) * k)));
  return { ...mean, data };
}

/** E[relMSE] of an unbiased image with this per-pixel variance: variance over (ref^2 + 0.01), as relativeMse. */
export function predictedRelMse(variance: LinearImage, reference: LinearImage): number {
  checkSameSize(variance, reference);
  let sum = 0;
  const n = variance.width * variance.height;
  for (let p = 0; p < n; p++) {
    for (let c = 0; c < 3; c++) {
      const r = reference.data[p * reference.channels + c];
      sum += variance.data[p * variance.channels + c] / (r * r + 0.01);
    }
  }
  return sum / (n * 3);
}
