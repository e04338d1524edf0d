/**
 * Collapses the binary SAH BVH (build.ts) into a BVH of up to BVH_WIDTH (4)
 * children per node, as Embree and Ylitie, Karras and Laine (HPG 2017) do:
 * a wide node starts with its binary node's two children and repeatedly
 * replaces the interior child of largest surface area by that child's own
 * two children, until it has BVH_WIDTH children or only leaves. Leaves stay
 * the binary build's (triangle ranges of at most MAX_LEAF_TRIANGLES).
 *
 * The traversal (bvh.glsl) pushes a visited node's hit children but the
 * nearest on its stack, so a path may need up to (children - 1) entries per
 * wide node on it. stackEntries is the most any root-to-leaf path needs;
 * when it would exceed MAX_WIDE_STACK (never seen outside adversarial
 * inputs) the BVH is collapsed to width 2 instead, whose paths need one
 * entry per level (the binary depth, at most MAX_BVH_DEPTH).
 */
import { MAX_BVH_DEPTH, type Bvh } from './build';

export const BVH_WIDTH = 4;
/** The GLSL traversal's stack entries (BVH_STACK_SIZE). */
export const MAX_WIDE_STACK = 64;

export interface WideBvh {
  /** Wide nodes in depth-first order (the root first): per node BVH_WIDTH binary node indices of its children, -1 for an empty slot. */
  children: Int32Array;
  nodeCount: number;
  /** Per binary interior node that is a wide node: its wide index (else -1). */
  wideOf: Int32Array;
  /** The most stack entries a traversal can hold (see above). */
  stackEntries: number;
}

const area = (b: Float32Array, i: number) => {
  const o = i * 6;
  const dx = b[o + 3] - b[o], dy = b[o + 4] - b[o + 1], dz = b[o + 5] - b[o + 2];
  return dx * dy + dy * dz + dz * dx;
};

export function collapseBvh(bvh: Bvh, width = BVH_WIDTH): WideBvh {
  const wide = collapseTo(bvh, width);
  if (wide.stackEntries <= MAX_WIDE_STACK || width === 2) return wide;
  return collapseTo(bvh, 2);
}

function collapseTo(bvh: Bvh, width: number): WideBvh {
  const { nodeData, nodeBounds, nodeCount } = bvh;
  const isLeaf = (i: number) => nodeData[i * 2 + 1] > 0;
  const children = new Int32Array(Math.max(1, nodeCount) * BVH_WIDTH).fill(-1);
  const wideOf = new Int32Array(nodeCount).fill(-1);
  let count = 0;
  let stackEntries = 0;
  // Depth-first with an explicit stack: [binary node, stack entries on the path above it].
  const todo: number[] = [0, 0];
  while (todo.length) {
    const above = todo.pop()!;
    const b = todo.pop()!;
    const w = count++;
    wideOf[b] = w;
    const o = w * BVH_WIDTH;
    if (isLeaf(b)) {
      // A root that is a leaf: one child, that leaf.
      children[o] = b;
      continue;
    }
    const kids = [b + 1, nodeData[b * 2]];
    while (kids.length < width) {
      let pick = -1;
      for (let k = 0; k < kids.length; k++) if (!isLeaf(kids[k]) && (pick < 0 || area(nodeBounds, kids[k]) > area(nodeBounds, kids[pick]))) pick = k;
      if (pick < 0) break;
      const n = kids[pick];
      kids.splice(pick, 1, n + 1, nodeData[n * 2]);
    }
    const path = above + kids.length - 1;
    stackEntries = Math.max(stackEntries, path);
    kids.forEach((k, c) => (children[o + c] = k));
    // Pushed in reverse so the first child's subtree is laid out first.
    for (let c = kids.length - 1; c >= 0; c--) if (!isLeaf(kids[c])) todo.push(kids[c], path);
  }
  if (width === 2 && stackEntries > MAX_BVH_DEPTH) throw new Error(`collapseBvh: ${stackEntries} stack entries exceed ${MAX_BVH_DEPTH}`);
  return { children: children.subarray(0, count * BVH_WIDTH), nodeCount: count, wideOf, stackEntries };
}
