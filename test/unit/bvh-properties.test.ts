/**
 * The BVH's structure and queries, property-tested with fast-check: every
 * triangle is in exactly one leaf and every node is reached once; every
 * node's box holds its children's boxes and its triangles; the traversal
 * (a TypeScript mirror of bvh.glsl over the packed textures) finds the same
 * closest hit as testing every triangle, and its any-hit query agrees on
 * whether anything is hit; the depth stays within the shader's stack.
 */
import { readFileSync } from 'node:fs';
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { buildBvh, MAX_BVH_DEPTH, type BvhMeshInput } from '../../src/render/bvh/build';
import { packBvh, type PackedBvh } from '../../src/render/bvh/pack';
import { bruteForce, traverseBvh, type Vec3 } from '../../src/render/bvh/traverse';
import { decodeMesh } from '../../src/scene/mesh';
import { icosphere } from '../support/icosphere';
import { random, triangleSoup } from '../support/bvhScenes';

function build(meshes: BvhMeshInput[]): PackedBvh {
  return packBvh(buildBvh(meshes), meshes);
}

/** Walks the packed tree; returns how often each node and each triangle is reached. */
function walk(packed: PackedBvh): { nodeVisits: Uint32Array; triangleVisits: Uint32Array; maxDepth: number } {
  const nodes = packed.nodes.data;
  const nodeVisits = new Uint32Array(packed.nodeCount);
  const triangleVisits = new Uint32Array(packed.triangleCount);
  let maxDepth = 0;
  const stack: [number, number][] = [[0, 0]];
  while (stack.length) {
    const [node, depth] = stack.pop()!;
    nodeVisits[node]++;
    maxDepth = Math.max(maxDepth, depth);
    const a = nodes[node * 8 + 3];
    const count = nodes[node * 8 + 7];
    if (count > 0) for (let j = a; j < a + count; j++) triangleVisits[j]++;
    else stack.push([node + 1, depth + 1], [a, depth + 1]);
  }
  return { nodeVisits, triangleVisits, maxDepth };
}

function expectBoundsNested(packed: PackedBvh): void {
  const nodes = packed.nodes.data;
  const tris = packed.triangles.data;
  const inside = (node: number, p: ArrayLike<number>, o: number) =>
    [0, 1, 2].every((k) => nodes[node * 8 + k] <= p[o + k] && p[o + k] <= nodes[node * 8 + 4 + k]);
  for (let node = 0; node < packed.nodeCount; node++) {
    const a = nodes[node * 8 + 3];
    const count = nodes[node * 8 + 7];
    if (count > 0) {
      for (let j = a; j < a + count; j++) for (let v = 0; v < 3; v++) expect(inside(node, tris, j * 12 + v * 4), `node ${node} holds triangle ${j}`).toBe(true);
    } else {
      for (const child of [node + 1, a]) {
        expect(inside(node, nodes, child * 8) && inside(node, nodes, child * 8 + 4), `node ${node} holds child ${child}`).toBe(true);
      }
    }
  }
}

const soupArb = fc.record({
  meshes: fc.array(fc.record({ count: fc.integer({ min: 1, max: 300 }), seed: fc.nat(), smooth: fc.boolean(), extent: fc.constantFrom(0.01, 1, 100) }), { minLength: 1, maxLength: 3 }),
});

function soups(spec: { meshes: { count: number; seed: number; smooth: boolean; extent: number }[] }): BvhMeshInput[] {
  return spec.meshes.map((m, i) => triangleSoup(m.count, m.seed, m.extent, i, m.smooth));
}

describe('BVH structure', () => {
  it('every triangle is in exactly one leaf, every node reached once, boxes nested, input triangles a permutation', () => {
    fc.assert(
      fc.property(soupArb, (spec) => {
        const meshes = soups(spec);
        const packed = build(meshes);
        const total = meshes.reduce((s, m) => s + m.indices.length / 3, 0);
        expect(packed.triangleCount).toBe(total);
        const { nodeVisits, triangleVisits } = walk(packed);
        expect(nodeVisits.every((v) => v === 1)).toBe(true);
        expect(triangleVisits.every((v) => v === 1)).toBe(true);
        expect([...packed.triangleOrder].sort((a, b) => a - b)).toEqual(Array.from({ length: total }, (_, i) => i));
        expectBoundsNested(packed);
      }),
      { numRuns: 60 },
    );
  });

  it('packs each triangle with its own vertices, material, mesh and normals', () => {
    const meshes = [triangleSoup(50, 1, 2, 7, false), triangleSoup(40, 2, 2, 3, true)];
    const packed = build(meshes);
    const tris = packed.triangles.data;
    for (let j = 0; j < packed.triangleCount; j++) {
      const id = packed.triangleOrder[j];
      const mesh = id < 50 ? 0 : 1;
      const local = id - (mesh ? 50 : 0);
      const m = meshes[mesh];
      expect(tris[j * 12 + 3]).toBe(m.material);
      expect(tris[j * 12 + 11]).toBe(mesh);
      for (let c = 0; c < 3; c++) {
        const v = m.indices[local * 3 + c];
        for (let k = 0; k < 3; k++) expect(tris[j * 12 + c * 4 + k]).toBe(m.positions[v * 3 + k]);
      }
      const normalTexel = tris[j * 12 + 7];
      if (!m.normals) expect(normalTexel).toBe(-1);
      else for (let c = 0; c < 3; c++) for (let k = 0; k < 3; k++) expect(tris[(normalTexel + c) * 4 + k]).toBe(m.normals[m.indices[local * 3 + c] * 3 + k]);
    }
  });

  it('depth stays within the shader stack for adversarial inputs', () => {
    // Exponentially spaced triangles make SAH splits peel one triangle at a time.
    const n = 5000;
    const positions = new Float32Array(n * 9);
    for (let t = 0; t < n; t++) {
      const x = Math.pow(1.004, t);
      positions.set([x, 0, 0, x + 1e-3 * x, 1, 0, x, 0, 1], t * 9);
    }
    const exponential = { positions, normals: null, indices: Uint32Array.from({ length: n * 3 }, (_, i) => i), material: 0 };
    // Identical triangles: no centroid extent at all.
    const same = { positions: new Float32Array(3000 * 9).map((_, i) => [0, 0, 0, 1, 0, 0, 0, 1, 0][i % 9]), normals: null, indices: Uint32Array.from({ length: 9000 }, (_, i) => i), material: 0 };
    for (const mesh of [exponential, same]) {
      const packed = build([mesh]);
      const { triangleVisits, maxDepth } = walk(packed);
      expect(maxDepth).toBeLessThanOrEqual(MAX_BVH_DEPTH);
      expect(packed.depth).toBe(maxDepth);
      expect(triangleVisits.every((v) => v === 1)).toBe(true);
      const hit = traverseBvh(packed, [0.5, 0.1, 5], [0, 0, -1], Infinity);
      expect(hit?.t).toBe(bruteForce(packed, [0.5, 0.1, 5], [0, 0, -1], Infinity)?.t);
    }
  });
});

const vec = (r: () => number, s: number): Vec3 => [(r() * 2 - 1) * s, (r() * 2 - 1) * s, (r() * 2 - 1) * s];

function expectSameHits(packed: PackedBvh, origin: Vec3, dir: Vec3, tMax: number): void {
  const fast = traverseBvh(packed, origin, dir, tMax);
  const slow = bruteForce(packed, origin, dir, tMax);
  expect(fast?.t).toBe(slow?.t);
  const any = traverseBvh(packed, origin, dir, tMax, true);
  expect(any !== null).toBe(slow !== null);
  if (any) expect(any.t).toBeLessThan(tMax);
}

describe('BVH queries equal brute force', () => {
  it('random soups, random rays (also aimed at triangles), random tMax', () => {
    fc.assert(
      fc.property(soupArb, fc.nat(), (spec, raySeed) => {
        const meshes = soups(spec);
        const packed = build(meshes);
        const r = random(raySeed);
        const extent = Math.max(...spec.meshes.map((m) => m.extent));
        for (let i = 0; i < 40; i++) {
          const origin = vec(r, extent * 2);
          // Half the rays aim at a random triangle's centroid, so most of them hit something.
          let dir = vec(r, 1);
          if (i % 2 === 0) {
            const j = Math.floor(r() * packed.triangleCount) * 12;
            const tris = packed.triangles.data;
            dir = [0, 1, 2].map((k) => (tris[j + k] + tris[j + 4 + k] + tris[j + 8 + k]) / 3 - origin[k]) as unknown as Vec3;
          }
          if (i % 10 === 1) dir = [0, 0, r() < 0.5 ? 1 : -1]; // axis-aligned: zero components
          const tMax = i % 3 === 0 ? Infinity : r() * extent * 4;
          expectSameHits(packed, origin, dir, tMax);
        }
      }),
      { numRuns: 80 },
    );
  });

  it('tiny BVHs (1, 2 and 3 triangles)', () => {
    for (const count of [1, 2, 3]) {
      const packed = build([triangleSoup(count, count, 1)]);
      const r = random(count);
      let hits = 0;
      for (let i = 0; i < 300; i++) {
        const j = Math.floor(r() * count) * 12;
        const origin = vec(r, 3);
        const target = [0, 1, 2].map((k) => (packed.triangles.data[j + k] + packed.triangles.data[j + 4 + k] + packed.triangles.data[j + 8 + k]) / 3);
        const dir = [0, 1, 2].map((k) => target[k] - origin[k]) as unknown as Vec3;
        expectSameHits(packed, origin, dir, Infinity);
        if (traverseBvh(packed, origin, dir, Infinity)) hits++;
      }
      expect(hits).toBe(300);
    }
  });

  it('the bunny and an icosphere, from outside and inside', async () => {
    const bunny = await decodeMesh(new Uint8Array(readFileSync(new URL('../fixtures/meshes/bunny.ply', import.meta.url))), 'bunny.ply');
    const packed = build([{ ...bunny, material: 0 }, { ...icosphere(3, false), material: 1 }]);
    const r = random(11);
    for (let i = 0; i < 1000; i++) expectSameHits(packed, vec(r, i % 2 ? 0.5 : 2), vec(r, 1), Infinity);
  });
});
