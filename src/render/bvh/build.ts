/**
 * Bounding volume hierarchy over world-space triangles of several meshes:
 * a binned surface-area-heuristic build in the style of pbrt-v4's
 * BVHAggregate (12 buckets along the centroid bounds' widest axis; split
 * cost 1 + SAH of the children against a leaf's cost = its triangle count),
 * flattened depth-first so an interior node's first child follows it and
 * only the second child's index is stored.
 *
 * The depth is capped at MAX_BVH_DEPTH so the GLSL traversal's fixed stack
 * (one entry per level) never overflows: a node that could not otherwise
 * reach leaves of MAX_LEAF_TRIANGLES triangles within the cap is split at
 * its centroid median instead, which halves the count at each level.
 */
import type { TriangleMesh } from '../../scene/types';

export interface BvhMeshInput extends TriangleMesh {
  /** Mesh-local material index carried by every triangle of this mesh (default 0); the mesh record's materialBase is added in the shader. */
  material?: number;
  /** The scene mesh index its triangles carry (default: its position in the input list; -1 in a shared group). */
  mesh?: number;
}

export interface Bvh {
  nodeCount: number;
  /** Per node 6 floats: min x y z, max x y z. */
  nodeBounds: Float32Array;
  /** Per node 2 uints: leaf (first triangle, count >= 1); interior (second child index, 0). */
  nodeData: Uint32Array;
  /** BVH triangle order -> input triangle id (the meshes' triangles concatenated in input order). */
  triangleOrder: Uint32Array;
  /** The deepest leaf's depth (root = 0); at most MAX_BVH_DEPTH. */
  depth: number;
}

export const MAX_BVH_DEPTH = 32;
export const MAX_LEAF_TRIANGLES = 8;
const BUCKETS = 12;
const TRAVERSAL_COST = 1;

/** Per-triangle bounds (6 floats) and centroids (3), for all meshes in order. */
function triangleBoxes(meshes: BvhMeshInput[]): { boxes: Float32Array; centroids: Float32Array } {
  const total = meshes.reduce((sum, m) => sum + m.indices.length / 3, 0);
  const boxes = new Float32Array(total * 6);
  const centroids = new Float32Array(total * 3);
  let t = 0;
  for (const mesh of meshes) {
    const { positions: p, indices } = mesh;
    for (let i = 0; i < indices.length; i += 3, t++) {
      for (let k = 0; k < 3; k++) {
        const a = p[indices[i] * 3 + k];
        const b = p[indices[i + 1] * 3 + k];
        const c = p[indices[i + 2] * 3 + k];
        const lo = Math.min(a, b, c);
        const hi = Math.max(a, b, c);
        boxes[t * 6 + k] = lo;
        boxes[t * 6 + 3 + k] = hi;
        centroids[t * 3 + k] = 0.5 * lo + 0.5 * hi;
      }
    }
  }
  return { boxes, centroids };
}

/** ceil(log2(ceil(n / MAX_LEAF_TRIANGLES))): levels a median split needs to reach leaves. */
function levelsNeeded(n: number): number {
  return Math.ceil(Math.log2(Math.max(1, Math.ceil(n / MAX_LEAF_TRIANGLES))));
}

function surfaceArea(b: Float64Array, o: number): number {
  const dx = b[o + 3] - b[o];
  const dy = b[o + 4] - b[o + 1];
  const dz = b[o + 5] - b[o + 2];
  return dx < 0 ? 0 : 2 * (dx * dy + dy * dz + dz * dx);
}

function emptyBox(b: Float64Array, o: number): void {
  b.fill(Infinity, o, o + 3);
  b.fill(-Infinity, o + 3, o + 6);
}

const EMPTY_BUCKETS = new Float64Array(BUCKETS * 6).map((_, i) => (i % 6 < 3 ? Infinity : -Infinity));

function growBox(b: Float64Array, o: number, src: Float64Array, s: number): void {
  for (let k = 0; k < 3; k++) {
    if (src[s + k] < b[o + k]) b[o + k] = src[s + k];
    if (src[s + 3 + k] > b[o + 3 + k]) b[o + 3 + k] = src[s + 3 + k];
  }
}

export function buildBvh(meshes: BvhMeshInput[]): Bvh {
  const { boxes, centroids } = triangleBoxes(meshes);
  const n = centroids.length / 3;
  if (n === 0) throw new Error('buildBvh: no triangles');
  const order = new Uint32Array(n).map((_, i) => i);
  const nodeBounds = new Float32Array(Math.max(1, 2 * n - 1) * 6);
  const nodeData = new Uint32Array(Math.max(1, 2 * n - 1) * 2);
  const scratch = new Float64Array(6); // the SAH sweeps' running box
  const buckets = new Float64Array(BUCKETS * 6);
  const counts = new Uint32Array(BUCKETS);
  const below = new Float64Array(BUCKETS); // SAH cost terms of splits after bucket i
  let nodeCount = 0;
  let maxDepth = 0;

  const build = (start: number, end: number, depth: number): void => {
    const node = nodeCount++;
    if (depth > maxDepth) maxDepth = depth;
    let minX = Infinity, minY = Infinity, minZ = Infinity, maxX = -Infinity, maxY = -Infinity, maxZ = -Infinity;
    let cminX = Infinity, cminY = Infinity, cminZ = Infinity, cmaxX = -Infinity, cmaxY = -Infinity, cmaxZ = -Infinity;
    for (let i = start; i < end; i++) {
      const t = order[i];
      const b = t * 6;
      if (boxes[b] < minX) minX = boxes[b];
      if (boxes[b + 1] < minY) minY = boxes[b + 1];
      if (boxes[b + 2] < minZ) minZ = boxes[b + 2];
      if (boxes[b + 3] > maxX) maxX = boxes[b + 3];
      if (boxes[b + 4] > maxY) maxY = boxes[b + 4];
      if (boxes[b + 5] > maxZ) maxZ = boxes[b + 5];
      const x = centroids[t * 3], y = centroids[t * 3 + 1], z = centroids[t * 3 + 2];
      if (x < cminX) cminX = x;
      if (x > cmaxX) cmaxX = x;
      if (y < cminY) cminY = y;
      if (y > cmaxY) cmaxY = y;
      if (z < cminZ) cminZ = z;
      if (z > cmaxZ) cmaxZ = z;
    }
    const o = node * 6;
    nodeBounds[o] = minX;
    nodeBounds[o + 1] = minY;
    nodeBounds[o + 2] = minZ;
    nodeBounds[o + 3] = maxX;
    nodeBounds[o + 4] = maxY;
    nodeBounds[o + 5] = maxZ;
    const count = end - start;
    const extents = [cmaxX - cminX, cmaxY - cminY, cmaxZ - cminZ];
    const axis = extents[0] >= extents[1] ? (extents[0] >= extents[2] ? 0 : 2) : extents[1] >= extents[2] ? 1 : 2;
    const lo = [cminX, cminY, cminZ][axis];
    const extent = extents[axis];
    let mid = -1;
    if (count === 1) {
      // a leaf
    } else if (extent > 0 && depth + levelsNeeded(count) < MAX_BVH_DEPTH) {
      const area = 2 * ((maxX - minX) * (maxY - minY) + (maxY - minY) * (maxZ - minZ) + (maxZ - minZ) * (maxX - minX));
      const split = sahSplit(start, end, axis, lo, extent, area);
      if (split === 'leaf' && count > MAX_LEAF_TRIANGLES) mid = medianSplit(start, end, axis);
      else if (split !== 'leaf') mid = split >= 0 ? partitionAt(start, end, axis, lo, extent, split) : medianSplit(start, end, axis);
    } else if (count > MAX_LEAF_TRIANGLES) {
      mid = medianSplit(start, end, axis);
    }
    if (mid < 0) {
      nodeData[node * 2] = start;
      nodeData[node * 2 + 1] = count;
      return;
    }
    if (mid <= start || mid >= end) mid = medianSplit(start, end, axis);
    build(start, mid, depth + 1);
    nodeData[node * 2] = nodeCount; // second child
    nodeData[node * 2 + 1] = 0;
    build(mid, end, depth + 1);
  };

  /** The best bucket boundary (split after bucket i), 'leaf' when a leaf is cheaper, -1 when no split separates. */
  const sahSplit = (start: number, end: number, axis: number, lo: number, extent: number, area: number): number | 'leaf' => {
    counts.fill(0);
    buckets.set(EMPTY_BUCKETS);
    const scale = BUCKETS / extent;
    for (let i = start; i < end; i++) {
      const t = order[i] * 6;
      const b = Math.min(BUCKETS - 1, Math.floor((centroids[order[i] * 3 + axis] - lo) * scale)) * 6;
      counts[b / 6]++;
      // Grow bucket b by triangle t's box (inlined: this is the build's hot loop).
      for (let k = 0; k < 3; k++) {
        if (boxes[t + k] < buckets[b + k]) buckets[b + k] = boxes[t + k];
        if (boxes[t + 3 + k] > buckets[b + 3 + k]) buckets[b + 3 + k] = boxes[t + 3 + k];
      }
    }
    // Sweep from the right: cost of everything above each boundary.
    emptyBox(scratch, 0);
    let countAbove = 0;
    for (let b = BUCKETS - 1; b > 0; b--) {
      growBox(scratch, 0, buckets, b * 6);
      countAbove += counts[b];
      below[b - 1] = countAbove * surfaceArea(scratch, 0);
    }
    emptyBox(scratch, 0);
    let countBelow = 0;
    let best = -1;
    let bestCost = Infinity;
    for (let b = 0; b < BUCKETS - 1; b++) {
      growBox(scratch, 0, buckets, b * 6);
      countBelow += counts[b];
      if (countBelow === 0 || countBelow === end - start) continue;
      const cost = countBelow * surfaceArea(scratch, 0) + below[b];
      if (cost < bestCost) [best, bestCost] = [b, cost];
    }
    if (best < 0) return -1;
    return TRAVERSAL_COST + bestCost / area >= end - start ? 'leaf' : best;
  };

  /** Moves triangles in buckets <= split before the others; returns the boundary. */
  const partitionAt = (start: number, end: number, axis: number, lo: number, extent: number, split: number): number => {
    const scale = BUCKETS / extent;
    let i = start;
    let j = end - 1;
    while (i <= j) {
      if (Math.min(BUCKETS - 1, Math.floor((centroids[order[i] * 3 + axis] - lo) * scale)) <= split) {
        i++;
      } else {
        const swap = order[i];
        order[i] = order[j];
        order[j--] = swap;
      }
    }
    return i;
  };

  const medianSplit = (start: number, end: number, axis: number): number => {
    const sorted = Array.from(order.subarray(start, end)).sort((a, b) => centroids[a * 3 + axis] - centroids[b * 3 + axis]);
    order.set(sorted, start);
    return start + (end - start >> 1);
  };

  build(0, n, 0);
  return {
    nodeCount,
    nodeBounds: nodeBounds.slice(0, nodeCount * 6),
    nodeData: nodeData.slice(0, nodeCount * 2),
    triangleOrder: order,
    depth: maxDepth,
  };
}
