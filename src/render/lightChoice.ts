/**
 * The choice of emitter for next-event estimation, by where the shading
 * point is (pure TypeScript; packed for lights/lights.glsl).
 *
 * A grid over the scene's objects: each cell has its own alias table over
 * the emitters, weighed by about the irradiance each can give a point of the
 * cell (the emitter's LightReach, src/lights/kind.ts, as pbrt-v4's
 * LightBounds::Importance does for a light BVH's nodes), mixed with a
 * uniform choice among the emitters that can light the cell at all. An
 * emitter gets probability 0 in a cell only when the whole ball around the
 * cell is behind its plane (one-sided planar lights) or outside its cone
 * (spots): then it cannot light any point there, and no sample is lost.
 * Points outside the grid use the global table (the choice by power of
 * version 2, emitterChoiceWeights). One texel per (table, emitter): (alias
 * threshold, alias, probability of this emitter, probability of its alias),
 * so a pick is one fetch, and the probability of emitter l at a point (the
 * MIS weight of a BSDF-sampled hit on l) is one fetch of entry l's .z.
 *
 * Measured on lights.json (bench/results/light-choice-2026-12-06.md):
 * the spot's and the point's glints on the metal sphere, found by
 * next-event estimation alone, were the heavy tail of the error; here the
 * spot is picked where its cone lands and never where it cannot.
 */
import type { LightReach } from '../lights/kind';
import type { Vec3 } from '../scene/types';
import { AliasBuilder, buildAliasTable } from './aliasTable';

/** Share of the uniform choice among the emitters that can light the cell (measured best of 0.1, 0.25, 0.5 on 2026-12-02's per-point version). */
export const UNIFORM_SHARE = 0.25;
/** Most cells per axis, and in all. */
const MAX_CELLS_PER_AXIS = 16;
const MAX_CELLS = 4096;
/** Most texels of the tables ((cells + 1) x emitters): 4 MB (64 emitters keep 4095 cells). */
const MAX_TABLE_TEXELS = 1 << 18;

export interface Box {
  min: Vec3;
  max: Vec3;
}

export interface LightChoice {
  /** The grid: its corner, cells per unit length, cells per axis (0: no grid, every point uses the global table). */
  origin: Vec3;
  inverseCellSize: Vec3;
  cells: [number, number, number];
  /** Tables: cells.x * cells.y * cells.z of the grid, then the global one. */
  tables: number;
  /** (tables x emitters) RGBA texels: (threshold, alias, pdf of the entry's emitter, pdf of its alias). */
  texels: Float32Array;
}

const sub = (a: Vec3, b: Vec3): Vec3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];

/**
 * About the irradiance an emitter gives a point of the ball (center,
 * radius); exactly 0 only where it gives none to any point of the ball.
 */
export function reachWeight(reach: LightReach, center: Vec3, radius: number): number {
  if (reach.strength <= 0) return 0;
  if (!reach.bound) return reach.strength;
  const c = reach.bound.center;
  const [x, y, z] = [center[0] - c[0], center[1] - c[1], center[2] - c[2]];
  const d2 = x * x + y * y + z * z;
  // Padded so that rounding never culls a point of the cell.
  const r = radius * (1 + 1e-3) + 1e-6;
  let weight = reach.strength / Math.max(d2, (radius + reach.bound.radius) ** 2, 1e-12);
  if (reach.front) {
    const n = reach.front;
    const height = x * n[0] + y * n[1] + z * n[2];
    if (height < -r) return 0;
    // The cosine at the light for the ball's best point, at least 0.1: only the zero must be exact.
    weight *= Math.min(1, Math.max(0.1, (height + r) / Math.sqrt(d2 + r * r)));
  }
  const d = Math.sqrt(d2);
  if (reach.cone && d > r) {
    const a = reach.cone.axis;
    const angle = Math.acos(Math.min(1, Math.max(-1, (x * a[0] + y * a[1] + z * a[2]) / d)));
    const spread = Math.asin(Math.min(1, r / d));
    if (angle - spread > Math.acos(reach.cone.cosCutoff) + 1e-4) return 0;
  }
  return weight;
}

/** A cell's probabilities: its weights normalized, mixed with a uniform choice among the emitters it can see; the global ones where it sees none. */
export function cellProbabilities(weights: readonly number[], global: readonly number[]): number[] {
  const probabilities = [...weights];
  mixCellWeights(probabilities, global);
  return probabilities;
}

/** cellProbabilities in place: `weights` become the cell's probabilities. */
function mixCellWeights(weights: { length: number; [i: number]: number }, global: readonly number[]): void {
  let total = 0;
  let lit = 0;
  for (let i = 0; i < weights.length; i++) {
    total += weights[i];
    if (weights[i] > 0) lit++;
  }
  const fallback = !(total > 0) || !Number.isFinite(total);
  for (let i = 0; i < weights.length; i++) {
    const mixed = weights[i] > 0 ? (1 - UNIFORM_SHARE) * (weights[i] / total) + UNIFORM_SHARE / lit : 0;
    weights[i] = fallback ? global[i] : mixed;
  }
}

/** Cells per axis for a box: about cubic cells, at most MAX_CELLS (and `budget`) in all. */
export function gridCells(box: Box, budget: number): [number, number, number] {
  const size = sub(box.max, box.min).map((s) => Math.max(s, 1e-6)) as Vec3;
  const total = Math.max(1, Math.min(MAX_CELLS, budget));
  let cell = Math.cbrt((size[0] * size[1] * size[2]) / total);
  let cells = size.map((s) => Math.min(MAX_CELLS_PER_AXIS, Math.max(1, Math.ceil(s / cell)))) as [number, number, number];
  while (cells[0] * cells[1] * cells[2] > total) {
    cell *= 1.1;
    cells = size.map((s) => Math.min(MAX_CELLS_PER_AXIS, Math.max(1, Math.ceil(s / cell)))) as [number, number, number];
  }
  return cells;
}

/** One table's texels from its probabilities (the global table: through buildAliasTable, as version 2 built it). */
function writeTable(texels: Float32Array, first: number, probabilities: readonly number[]): void {
  const alias = buildAliasTable(probabilities);
  probabilities.forEach((_, i) => {
    const a = alias.alias[i];
    texels.set([alias.threshold[i], a, alias.pdf[i], alias.pdf[a]], (first + i) * 4);
  });
}

/**
 * A cell's table, on arrays reused from cell to cell: a grid of 4096 cells is
 * rebuilt on every edit of a light (dragging one repacks the scene each
 * frame), so a cell allocates nothing.
 */
class CellTables {
  private readonly weights: Float64Array;
  private readonly alias: AliasBuilder;

  constructor(private readonly count: number) {
    this.weights = new Float64Array(count);
    this.alias = new AliasBuilder(count);
  }

  /** Writes the table of the cell (center, radius) at texel `first`. */
  write(texels: Float32Array, first: number, reaches: readonly LightReach[], center: Vec3, radius: number, global: readonly number[]): void {
    const { count, weights, alias } = this;
    for (let i = 0; i < count; i++) weights[i] = reachWeight(reaches[i], center, radius);
    mixCellWeights(weights, global);
    alias.build(weights);
    for (let i = 0; i < count; i++) {
      const a = alias.alias[i];
      texels.set([alias.threshold[i], a, weights[i], weights[a]], (first + i) * 4);
    }
  }
}

/**
 * The tables for emitters with these reaches and global choice weights, over
 * `box` (null: no grid). No grid either with fewer than two emitters, or
 * when every emitter is at infinity (the same from everywhere).
 */
export function buildLightChoice(reaches: readonly LightReach[], globalWeights: readonly number[], box: Box | null): LightChoice {
  const count = reaches.length;
  const globalTotal = globalWeights.reduce((sum, w) => sum + w, 0);
  const global = globalWeights.map((w) => (globalTotal > 0 ? w / globalTotal : 0));
  const useGrid = box !== null && count >= 2 && reaches.some((r) => r.bound !== null);
  const cells: [number, number, number] = useGrid ? gridCells(box, Math.floor(MAX_TABLE_TEXELS / count) - 1) : [0, 0, 0];
  const gridTables = cells[0] * cells[1] * cells[2];
  const tables = gridTables + 1;
  const texels = new Float32Array(tables * Math.max(count, 1) * 4);
  const origin: Vec3 = box ? [...box.min] : [0, 0, 0];
  const cellSize = box ? ([0, 1, 2].map((k) => (box.max[k] - box.min[k]) / Math.max(cells[k], 1)) as Vec3) : ([1, 1, 1] as Vec3);
  const radius = Math.hypot(...cellSize) / 2;
  const tablesOfCells = new CellTables(count);
  const center: Vec3 = [0, 0, 0];
  for (let z = 0; z < cells[2]; z++) {
    for (let y = 0; y < cells[1]; y++) {
      for (let x = 0; x < cells[0]; x++) {
        center[0] = origin[0] + (x + 0.5) * cellSize[0];
        center[1] = origin[1] + (y + 0.5) * cellSize[1];
        center[2] = origin[2] + (z + 0.5) * cellSize[2];
        tablesOfCells.write(texels, (x + cells[0] * (y + cells[1] * z)) * count, reaches, center, radius, global);
      }
    }
  }
  if (count > 0) writeTable(texels, gridTables * count, globalWeights);
  return {
    origin,
    inverseCellSize: cellSize.map((s) => (s > 0 ? 1 / s : 0)) as Vec3,
    cells,
    tables,
    texels,
  };
}

/** The table a point uses (the grid's cell holding it, else the global table), as the shader finds it. */
export function tableAt(choice: LightChoice, p: Vec3): number {
  const g = [0, 1, 2].map((k) => (p[k] - choice.origin[k]) * choice.inverseCellSize[k]);
  const inside = g.every((v, k) => v >= 0 && v < choice.cells[k]);
  if (!inside) return choice.tables - 1;
  const [x, y, z] = g.map((v, k) => Math.min(Math.floor(v), choice.cells[k] - 1));
  return x + choice.cells[0] * (y + choice.cells[1] * z);
}
