/**
 * A TypeScript mirror of src/shaders/scene/bvh.glsl over the packed texture
 * data: the same layout, the same steps (one wide node, or two triangles of a leaf, each),
 * nearest-child-first order, fixed-size stack, conservative slab test and
 * watertight ray-triangle test (Woop, Benthin and Wald, JCGT 2013). Tests
 * compare it with brute force and with the GLSL.
 */
import { BVH_ROOT_NODE, nodeChildren, BVH_ROW_TRIANGLES, BVH_TEXTURE_WIDTH, triangleAt, triangleTexel, type PackedBvh } from './pack';
import { MAX_WIDE_STACK } from './wide';

export type Vec3 = readonly [number, number, number];

export interface BvhHit {
  /** Triangle index in BVH order (packed.triangleOrder maps it to the input). */
  triangle: number;
  t: number;
  /** Barycentric weights of v1 and v2 (v0's is 1 - b1 - b2). */
  b1: number;
  b2: number;
}

/** Pads the slab test's exit distance (pbrt's 1 + 2 gamma(3), plus ulps for approximate GPU division), so a box never loses a hit on its face. */
export const BOX_EXIT_SCALE = 1.000001;

/** Per-ray constants of the watertight test: the axis permutation and shear. */
interface ShearedRay {
  origin: Vec3;
  kx: number;
  ky: number;
  kz: number;
  sx: number;
  sy: number;
  sz: number;
}

export function shearRay(origin: Vec3, dir: Vec3): ShearedRay {
  const ad = dir.map(Math.abs);
  const kz = ad[0] > ad[1] ? (ad[0] > ad[2] ? 0 : 2) : ad[1] > ad[2] ? 1 : 2;
  const kx = (kz + 1) % 3;
  const ky = (kx + 1) % 3;
  return { origin, kx, ky, kz, sx: dir[kx] / dir[kz], sy: dir[ky] / dir[kz], sz: 1 / dir[kz] };
}

/** Watertight test of triangle j (its texels in `tex`); a hit closer than tMax, or null. */
export function intersectTriangle(tex: Float32Array, j: number, ray: ShearedRay, tMax: number): BvhHit | null {
  const o = triangleTexel(j) * 4;
  const { origin, kx, ky, kz, sx, sy, sz } = ray;
  // Vertex c relative to the origin, permuted and sheared: x, y across the ray, z = t along it.
  const sheared = (c: number, axis: 0 | 1 | 2): number => {
    const pz = tex[o + c * 4 + kz] - origin[kz];
    if (axis === 2) return sz * pz;
    const k = axis === 0 ? kx : ky;
    return tex[o + c * 4 + k] - origin[k] - (axis === 0 ? sx : sy) * pz;
  };
  const ax = sheared(0, 0), ay = sheared(0, 1);
  const bx = sheared(1, 0), by = sheared(1, 1);
  const cx = sheared(2, 0), cy = sheared(2, 1);
  const u = cx * by - cy * bx;
  const v = ax * cy - ay * cx;
  const w = bx * ay - by * ax;
  if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return null;
  const det = u + v + w;
  if (det === 0) return null;
  const t = (u * sheared(0, 2) + v * sheared(1, 2) + w * sheared(2, 2)) / det;
  if (!(t > 0 && t < tMax)) return null;
  return { triangle: j, t, b1: v / det, b2: w / det };
}

/** Entry distance of the ray into the box at floats lo .. lo + 2 and hi .. hi + 2 of `data`, or Infinity when it misses before tMax. */
export function boxEntry(data: Float32Array, lo: number, hi: number, origin: Vec3, invDir: Vec3, tMax: number): number {
  let enter = 0;
  let exit = tMax;
  for (let k = 0; k < 3; k++) {
    const t0 = (data[lo + k] - origin[k]) * invDir[k];
    const t1 = (data[hi + k] - origin[k]) * invDir[k];
    enter = Math.max(enter, Math.min(t0, t1));
    exit = Math.min(exit, Math.max(t0, t1));
  }
  return enter <= exit * BOX_EXIT_SCALE ? enter : Infinity;
}

/** 1 / d with zero components replaced by a huge value of the same sign (no 0 * inf = NaN in the slab test). */
export function safeInverse(dir: Vec3): Vec3 {
  return dir.map((d) => (Object.is(d, -0) || d < 0 ? -1 : 1) / Math.max(Math.abs(d), 1e-30)) as unknown as Vec3;
}

/** Work of one traversal (bench/bvh-stats.ts): per loop step 0 for a node, else the triangles it tested (1 or 2); and stack pops. */
export interface TraceStats {
  steps: number[];
  pops: number;
  hit: BvhHit | null;
}

export function traceStats(packed: PackedBvh, origin: Vec3, dir: Vec3, tMax: number, anyHit: boolean): TraceStats {
  const stats: TraceStats = { steps: [], pops: 0, hit: null };
  stats.hit = traverseBvh(packed, origin, dir, tMax, anyHit, stats);
  return stats;
}

/** Column of a row's last triangle (bvh.glsl: its pair is zero padding). */
const LAST_COLUMN = (BVH_ROW_TRIANGLES - 1) * 3;

/**
 * Closest hit (anyHit false) or the first hit found (anyHit true) before
 * tMax; null when none. The current item is a node or a leaf's pending
 * triangles. A triangle step tests the next two (one at a row's end); a
 * node step tests the 4 children's boxes, sorts them by entry distance,
 * farthest first and the missed ones last (the GLSL's sorting network, so
 * ties go the same way), and pushes the hit ones: the nearest is on top.
 * With no current item, one is popped (after every node step). `root`: the
 * group's root node (packed.roots; the first group's by default).
 */
export function traverseBvh(packed: PackedBvh, origin: Vec3, dir: Vec3, tMax: number, anyHit = false, stats?: TraceStats, root = BVH_ROOT_NODE): BvhHit | null {
  const tex = packed.texture.data;
  const invDir = safeInverse(dir);
  const ray = shearRay(origin, dir);
  const stack: Item[] = [];
  let best: BvhHit | null = null;
  let limit = tMax;
  let item: Item | null = { node: root };
  while (item) {
    if ('texel' in item) {
      const j = triangleAt(item.texel);
      const lastOfRow = item.texel % BVH_TEXTURE_WIDTH === LAST_COLUMN;
      const tested: number = lastOfRow ? 1 : Math.min(2, item.count);
      stats?.steps.push(tested);
      for (let k = 0; k < tested; k++) {
        const hit = intersectTriangle(tex, j + k, ray, limit);
        if (hit) {
          best = hit;
          limit = hit.t;
          if (anyHit) return best;
        }
      }
      const count: number = item.count - (lastOfRow ? 1 : 2);
      item = count > 0 ? { texel: triangleTexel(j + tested), count } : null;
    } else {
      stats?.steps.push(0);
      for (const hit of nodeHits(tex, item.node, origin, invDir, limit)) stack.push(hit);
      if (stack.length > MAX_WIDE_STACK + 1) throw new Error('BVH stack overflow');
      item = null;
    }
    if (!item && stack.length > 0) {
      item = stack.pop()!;
      if (stats) stats.pops++;
    }
  }
  return best;
}

/** A traversal item: a node (its first texel), or a leaf's triangles from `texel` (`count` of them). */
type Item = { node: number } | { texel: number; count: number };

/** The comparators of bvh.glsl's sorting network (bvhOrder: the second goes first only when strictly farther). */
export const SORT_NETWORK = [
  [0, 1],
  [2, 3],
  [0, 2],
  [1, 3],
  [1, 2],
] as const;

/** The children of the node at `texel` whose boxes the ray enters before tMax, farthest first (bvh.glsl's sorting network). */
function nodeHits(tex: Float32Array, texel: number, origin: Vec3, invDir: Vec3, tMax: number): Item[] {
  const entries = nodeChildren(tex, texel).map((child) => {
    if (!child) return { key: -1, item: { node: -1 } as Item };
    let enter = 0;
    let exit = tMax;
    for (let k = 0; k < 3; k++) {
      const t0 = (child.lo[k] - origin[k]) * invDir[k];
      const t1 = (child.hi[k] - origin[k]) * invDir[k];
      enter = Math.max(enter, Math.min(t0, t1));
      exit = Math.min(exit, Math.max(t0, t1));
    }
    const hit = enter <= exit * BOX_EXIT_SCALE;
    return { key: hit ? enter : -1, item: (child.count > 0 ? { texel: child.ref, count: child.count } : { node: child.ref }) as Item };
  });
  for (const [a, b] of SORT_NETWORK) {
    if (entries[b].key > entries[a].key) [entries[a], entries[b]] = [entries[b], entries[a]];
  }
  return entries.filter((e) => e.key >= 0).map((e) => e.item);
}

/** Every triangle tested (or only triangle `only`): the reference for traverseBvh. */
export function bruteForce(packed: PackedBvh, origin: Vec3, dir: Vec3, tMax: number, only?: number): BvhHit | null {
  const ray = shearRay(origin, dir);
  let best: BvhHit | null = null;
  for (let j = only ?? 0; j < (only === undefined ? packed.triangleCount : only + 1); j++) {
    const hit = intersectTriangle(packed.texture.data, j, ray, best ? best.t : tMax);
    if (hit) best = hit;
  }
  return best;
}

/** The first texel of triangle j's corner texture coordinates (pack.ts: its attributes), or -1 when it has none. */
export function uvTexel(tex: Float32Array, j: number): number {
  const a = tex[triangleTexel(j) * 4 + 7];
  if (a >= 0) return tex[a * 4 + 3] > 0 ? a + 3 : -1;
  return a <= -2 ? -2 - a : -1;
}

/** The hit's texture coordinates, its corners' interpolated (bvh.glsl bvhSurface's uv); (0, 0) without. */
export function hitUv(packed: PackedBvh, hit: BvhHit): [number, number] {
  const tex = packed.texture.data;
  const k = uvTexel(tex, hit.triangle);
  if (k < 0) return [0, 0];
  const b0 = 1 - hit.b1 - hit.b2;
  return [0, 1].map((c) => b0 * tex[k * 4 + c] + hit.b1 * tex[k * 4 + 2 + c] + hit.b2 * tex[(k + 1) * 4 + c]) as [number, number];
}

/** The first texel of triangle j's corner vertex colors (pack.ts: its attributes), or -1 when it has none. */
export function colorTexel(tex: Float32Array, j: number): number {
  const a = tex[triangleTexel(j) * 4 + 7];
  if (a >= 0) return tex[(a + 1) * 4 + 3] > 0 ? a + 3 + (tex[a * 4 + 3] > 0 ? 2 : 0) : -1;
  return a <= -2 && tex[(-2 - a + 1) * 4 + 2] > 0 ? -2 - a + 2 : -1;
}

/** The hit's vertex color, its corners' interpolated (bvh.glsl bvhSurface's color); white without. */
export function hitColor(packed: PackedBvh, hit: BvhHit): [number, number, number] {
  const tex = packed.texture.data;
  const k = colorTexel(tex, hit.triangle);
  if (k < 0) return [1, 1, 1];
  const b0 = 1 - hit.b1 - hit.b2;
  return [0, 1, 2].map((c) => b0 * tex[k * 4 + c] + hit.b1 * tex[(k + 1) * 4 + c] + hit.b2 * tex[(k + 2) * 4 + c]) as [number, number, number];
}
