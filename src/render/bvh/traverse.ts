/**
 * A TypeScript mirror of src/shaders/scene/bvh.glsl over the packed texture
 * data: the same node layout, nearest-child-first order, fixed-size stack,
 * conservative slab test and watertight ray-triangle test (Woop, Benthin and
 * Wald, JCGT 2013). Tests compare it with brute force and with the GLSL.
 */
import { BVH_TRIANGLE_TEXELS, type PackedBvh } from './pack';
import { MAX_BVH_DEPTH } from './build';

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

/** Watertight test of triangle j; a hit closer than tMax, or null. */
export function intersectTriangle(tex: Float32Array, j: number, ray: ShearedRay, tMax: number): BvhHit | null {
  const o = j * BVH_TRIANGLE_TEXELS * 4;
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

/** Entry distance of the ray into node's box, or Infinity when it misses before tMax. */
export function boxEntry(nodes: Float32Array, node: number, origin: Vec3, invDir: Vec3, tMax: number): number {
  let enter = 0;
  let exit = tMax;
  for (let k = 0; k < 3; k++) {
    const t0 = (nodes[node * 8 + k] - origin[k]) * invDir[k];
    const t1 = (nodes[node * 8 + 4 + k] - origin[k]) * invDir[k];
    enter = Math.max(enter, Math.min(t0, t1));
    exit = Math.min(exit, Math.max(t0, t1));
  }
  return enter <= exit * BOX_EXIT_SCALE ? enter : Infinity;
}

/** 1 / d with zero components replaced by a huge value of the same sign (no 0 * inf = NaN in the slab test). */
export function safeInverse(dir: Vec3): Vec3 {
  return dir.map((d) => (Object.is(d, -0) || d < 0 ? -1 : 1) / Math.max(Math.abs(d), 1e-30)) as unknown as Vec3;
}

/** Closest hit (anyHit false) or the first hit found (anyHit true) before tMax; null when none. */
export function traverseBvh(packed: PackedBvh, origin: Vec3, dir: Vec3, tMax: number, anyHit = false): BvhHit | null {
  const nodes = packed.nodes.data;
  const tris = packed.triangles.data;
  const invDir = safeInverse(dir);
  const ray = shearRay(origin, dir);
  const stack: number[] = [];
  const stackT: number[] = [];
  let best: BvhHit | null = null;
  let limit = tMax;
  let node = boxEntry(nodes, 0, origin, invDir, limit) < Infinity ? 0 : -1;
  while (node >= 0) {
    const a = nodes[node * 8 + 3];
    const count = nodes[node * 8 + 7];
    let next = -1;
    if (count > 0) {
      for (let j = a; j < a + count; j++) {
        const hit = intersectTriangle(tris, j, ray, limit);
        if (hit) {
          best = hit;
          limit = hit.t;
          if (anyHit) return best;
        }
      }
    } else {
      const left = node + 1;
      const right = a;
      const tl = boxEntry(nodes, left, origin, invDir, limit);
      const tr = boxEntry(nodes, right, origin, invDir, limit);
      if (tl < Infinity && tr < Infinity) {
        if (stack.length >= MAX_BVH_DEPTH) throw new Error('BVH stack overflow');
        stack.push(tl <= tr ? right : left);
        stackT.push(Math.max(tl, tr));
        next = tl <= tr ? left : right;
      } else if (tl < Infinity) next = left;
      else if (tr < Infinity) next = right;
    }
    while (next < 0 && stack.length > 0) {
      const t = stackT.pop()!;
      const candidate = stack.pop()!;
      if (t <= limit) next = candidate;
    }
    node = next;
  }
  return best;
}

/** Every triangle tested: the reference for traverseBvh. */
export function bruteForce(packed: PackedBvh, origin: Vec3, dir: Vec3, tMax: number): BvhHit | null {
  const ray = shearRay(origin, dir);
  let best: BvhHit | null = null;
  for (let j = 0; j < packed.triangleCount; j++) {
    const hit = intersectTriangle(packed.triangles.data, j, ray, best ? best.t : tMax);
    if (hit) best = hit;
  }
  return best;
}
