/**
 * The importance-sampling distribution of an environment map: piecewise
 * constant over cells in (u, v), each row weighted by its solid angle,
 * drawn in constant time by alias tables (Walker/Vose), so the shader needs
 * one texel fetch per dimension to sample and one per dimension for the pdf.
 *
 * Cells are the patches of the map's bilinear lookup (scene format): cell
 * (i, j) spans u from the centre of column i to the centre of column i + 1
 * (wrapping: u in [(i + 0.5) / W, (i + 1.5) / W]) and v from row j to row
 * j + 1 (v in [j / R, (j + 1) / R], R = H - 1 rows of cells, rows sitting at
 * v = j / (H - 1)). Its weight is the mean luminance of its four corner
 * texels, which is exactly the mean of the bilinear radiance over the patch:
 * the pdf is zero only where the radiance is zero over the whole patch.
 *
 * Densities: pdf(u, v) = marginal[j] * conditional[i | j] * W * R on the
 * unit square; per solid angle pdf(u, v) / (2 pi^2 sin theta), theta = pi v.
 *
 * Texture layout (RGBA32F, one texel per entry, ready to upload):
 *   marginal:    R x 1 texels, one per row of cells
 *   conditional: W x R texels, one per cell, a table per row
 * each texel (keep probability, alias index, probability of the entry,
 * probability of its alias): a draw costs one fetch per dimension and
 * returns the probability of what it drew. Alias tables rather than CDFs:
 * a CDF needs a binary search (12 dependent fetches in a loop for 4k
 * entries, every step run by all lanes on SwiftShader) or a tabulated
 * inverse, which is only approximately the density it claims.
 */
import type { EnvironmentImage } from '../types';

export interface EnvironmentDistribution {
  /** Columns of cells (the map's width). */
  width: number;
  /** Rows of cells: the map's height - 1 (1 for a one-row map). */
  rows: number;
  marginal: Float32Array;
  conditional: Float32Array;
  /**
   * The integral of the map's luminance over the sphere (per steradian
   * texel units x sr) of the piecewise-constant approximation: the map's
   * power up to the scene's scale, for choosing between lights.
   */
  integral: number;
}

/** Luminance of row y into `out` (texels are >= 0 after decoding; clamped again for safety). */
function rowLuminance(image: EnvironmentImage, y: number, out: Float64Array): void {
  const { rgb, width } = image;
  for (let x = 0, i = y * width * 3; x < width; x++, i += 3) {
    const l = 0.2126 * rgb[i] + 0.7152 * rgb[i + 1] + 0.0722 * rgb[i + 2];
    out[x] = l > 0 ? l : 0;
  }
}

/** Cell weights of a row of cells: the mean of each cell's four corner texels (columns wrap). */
function cellMeans(top: Float64Array, bottom: Float64Array, width: number, out: Float64Array): number {
  let sum = 0;
  for (let i = 0; i < width; i++) {
    const next = i + 1 < width ? i + 1 : 0;
    const v = (top[i] + top[next] + bottom[i] + bottom[next]) * 0.25;
    out[i] = v;
    sum += v;
  }
  return sum;
}

/** Solid angle of band j over 2 pi: cos(theta_j) - cos(theta_j+1), the integral of sin theta. */
function bandWeight(j: number, rows: number): number {
  return Math.cos((Math.PI * j) / rows) - Math.cos((Math.PI * (j + 1)) / rows);
}

/** Work arrays of writeAliasTable, reused across rows. */
interface AliasScratch {
  stacks: Int32Array;
  scaled: Float64Array;
  keep: Float64Array;
  alias: Int32Array;
}

function aliasScratch(n: number): AliasScratch {
  return { stacks: new Int32Array(n), scaled: new Float64Array(n), keep: new Float64Array(n), alias: new Int32Array(n) };
}

/**
 * Vose's alias method for the `n` non-negative `weights` (sum `sum` > 0),
 * written into `table` at `offset` with 4 floats per entry: x = keep
 * probability (the entry itself when the remapped sample is below it, else
 * its alias), y = alias index, z = probability, w = probability of the alias.
 * The small and large worklists share one array (small from the front,
 * large from the back); the table is written in one sequential pass.
 */
function writeAliasTable(weights: Float64Array, sum: number, n: number, table: Float32Array, offset: number, work: AliasScratch): void {
  const { stacks, scaled, keep, alias } = work;
  const scale = n / sum;
  let small = 0;
  let large = n;
  for (let i = 0; i < n; i++) {
    const x = weights[i] * scale;
    scaled[i] = x;
    keep[i] = 1; // what is left at the end is 1 up to rounding: keeps itself
    alias[i] = i;
    if (x < 1) stacks[small++] = i;
    else stacks[--large] = i;
  }
  while (small > 0 && large < n) {
    const less = stacks[--small];
    const more = stacks[large];
    keep[less] = scaled[less];
    alias[less] = more;
    const left = scaled[more] + scaled[less] - 1;
    scaled[more] = left;
    if (left < 1) {
      large++;
      stacks[small++] = more;
    }
  }
  const inverse = 1 / sum;
  for (let i = 0, t = offset; i < n; i++, t += 4) {
    table[t] = keep[i];
    table[t + 1] = alias[i];
    table[t + 2] = weights[i] * inverse;
    table[t + 3] = weights[alias[i]] * inverse;
  }
}

export interface DistributionOptions {
  /**
   * pbrt-v4's compensated distribution: sample max(L - average L, 0), which
   * spends no light samples where BSDF sampling already does well (dim,
   * smooth parts of the map). The pdf is then zero there: only valid with
   * MIS against BSDF sampling that can reach every direction. A map with
   * nothing above its average (constant) falls back to the plain one.
   */
  compensated?: boolean;
}

export function buildEnvironmentDistribution(image: EnvironmentImage, options: DistributionOptions = {}): EnvironmentDistribution {
  const { width, height } = image;
  const rows = Math.max(height - 1, 1);
  const conditional = new Float32Array(width * rows * 4);
  const marginal = new Float32Array(rows * 4);
  const scratch = aliasScratch(Math.max(width, rows));
  const cell = new Float64Array(width);
  const rowWeight = new Float64Array(rows);
  const average = options.compensated ? averageLuminance(image) : 0;
  let top = new Float64Array(width);
  let bottom = new Float64Array(width);
  rowLuminance(image, 0, bottom);
  let integral = 0;
  for (let j = 0; j < rows; j++) {
    [top, bottom] = [bottom, top];
    rowLuminance(image, Math.min(j + 1, height - 1), bottom);
    let sum = cellMeans(top, bottom, width, cell);
    integral += (sum / width) * bandWeight(j, rows) * 2 * Math.PI;
    if (average > 0) sum = subtractClamped(cell, average);
    // A black row is sampled uniformly (it gets no marginal mass unless the whole map is black).
    if (sum > 0) writeAliasTable(cell, sum, width, conditional, j * width * 4, scratch);
    else writeAliasTable(cell.fill(1), width, width, conditional, j * width * 4, scratch);
    // Mean sampled weight of the row times its solid angle / (2 pi).
    rowWeight[j] = (sum / width) * bandWeight(j, rows);
  }
  let total = rowWeight.reduce((a, b) => a + b, 0);
  if (!(total > 0) && average > 0) return buildEnvironmentDistribution(image);
  // A black map: uniform over the sphere (the caller gives it no light-selection probability anyway).
  if (!(total > 0)) {
    for (let j = 0; j < rows; j++) rowWeight[j] = bandWeight(j, rows);
    total = 2;
  }
  writeAliasTable(rowWeight, total, rows, marginal, 0, scratch);
  return { width, rows, marginal, conditional, integral };
}

/** Mean luminance over the sphere, from the texel rows weighted by sin(theta) (a heuristic's constant: need not be exact). */
function averageLuminance(image: EnvironmentImage): number {
  const row = new Float64Array(image.width);
  let sum = 0;
  let weights = 0;
  for (let y = 0; y < image.height; y++) {
    const w = image.height > 1 ? Math.sin((Math.PI * y) / (image.height - 1)) : 1;
    if (w <= 0) continue;
    rowLuminance(image, y, row);
    sum += (w * row.reduce((a, b) => a + b, 0)) / image.width;
    weights += w;
  }
  return weights > 0 ? sum / weights : 0;
}

/** cell[i] = max(cell[i] - offset, 0); returns the new sum. */
function subtractClamped(cell: Float64Array, offset: number): number {
  let sum = 0;
  for (let i = 0; i < cell.length; i++) {
    const v = cell[i] > offset ? cell[i] - offset : 0;
    cell[i] = v;
    sum += v;
  }
  return sum;
}

/** Alias-table draw of one entry from u in [0, 1): the entry and u remapped to [0, 1) within it. */
function drawAlias(table: Float32Array, offset: number, n: number, u: number): { index: number; t: number } {
  const x = u * n;
  const i = Math.min(Math.floor(x), n - 1);
  const f = Math.min(x - i, 1);
  const keep = table[offset + i * 4];
  if (f < keep) return { index: i, t: f / keep };
  return { index: table[offset + i * 4 + 1], t: Math.min((f - keep) / (1 - keep), 1) };
}

export interface EnvironmentUvSample {
  /** Map coordinates (scene format: u across from the left, v down from the top). */
  u: number;
  v: number;
  /** Density on the unit square of (u, v). */
  pdfUv: number;
}

/** TypeScript reference of the shader's sampler: a point of the map drawn from the distribution. */
export function sampleEnvironmentDistribution(d: EnvironmentDistribution, u1: number, u2: number): EnvironmentUvSample {
  const row = drawAlias(d.marginal, 0, d.rows, u2);
  const column = drawAlias(d.conditional, row.index * d.width * 4, d.width, u1);
  const u = ((column.index + column.t + 0.5) / d.width) % 1;
  const v = (row.index + row.t) / d.rows;
  return { u, v, pdfUv: cellPdfUv(d, column.index, row.index) };
}

function cellPdfUv(d: EnvironmentDistribution, column: number, row: number): number {
  return d.marginal[row * 4 + 2] * d.conditional[(row * d.width + column) * 4 + 2] * d.width * d.rows;
}

/** Density on the unit square at map coordinates (u, v). */
export function environmentDistributionPdfUv(d: EnvironmentDistribution, u: number, v: number): number {
  const shifted = u - 0.5 / d.width;
  const column = Math.min(Math.floor((shifted - Math.floor(shifted)) * d.width), d.width - 1);
  const row = Math.min(Math.max(Math.floor(v * d.rows), 0), d.rows - 1);
  return cellPdfUv(d, column, row);
}

/** Solid-angle density at map coordinates (u, v): the (u, v) density over the Jacobian 2 pi^2 sin theta. */
export function environmentDistributionPdf(d: EnvironmentDistribution, u: number, v: number): number {
  const sinTheta = Math.sin(Math.PI * v);
  return sinTheta > 0 ? environmentDistributionPdfUv(d, u, v) / (2 * Math.PI * Math.PI * sinTheta) : 0;
}
