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
import { MAX_WIDE_STACK } from '../../src/render/bvh/wide';
import { BVH_NODE_TEXELS, BVH_ROOT_NODE, MAX_COLORED_TRIANGLES, MAX_TRIANGLES, nodeChildren, packBvh, triangleAt, triangleTexel, type PackedBvh } from '../../src/render/bvh/pack';
import { bruteForce, colorTexel, hitColor, hitUv, traverseBvh, uvTexel, type Vec3 } from '../../src/render/bvh/traverse';
import { decodeMesh } from '../../src/scene/mesh';
import { icosphere } from '../support/icosphere';
import { random, triangleSoup } from '../support/bvhScenes';

function build(meshes: BvhMeshInput[]): PackedBvh {
  return packBvh(buildBvh(meshes), meshes);
}

/** The children of the node at texel q: box (lo, hi), and a leaf's triangles (first `ref`, `count`) or a child node (`ref`, count 0); empty slots left out. */
function children(packed: PackedBvh, q: number) {
  return nodeChildren(packed.texture.data, q)
    .filter((c) => c !== null)
    .map((c) => {
      if (c.count > 0) expect(triangleTexel(triangleAt(c.ref)), `node ${q}: a leaf starts at a triangle's first texel`).toBe(c.ref);
      return { lo: c.lo, hi: c.hi, ref: c.count > 0 ? triangleAt(c.ref) : c.ref, count: c.count };
    });
}

/** Walks the packed tree; returns how often each stored node and each triangle is reached, and the most stack entries a path needs (one per child but one of each wide node on it). */
function walk(packed: PackedBvh): { nodeVisits: Map<number, number>; triangleVisits: Uint32Array; maxDepth: number } {
  const nodeVisits = new Map<number, number>();
  const triangleVisits = new Uint32Array(packed.triangleCount);
  let maxDepth = 0;
  const stack: [number, number][] = [[BVH_ROOT_NODE, 0]];
  while (stack.length) {
    const [q, depth] = stack.pop()!;
    nodeVisits.set(q, (nodeVisits.get(q) ?? 0) + 1);
    const kids = children(packed, q);
    const below = depth + kids.length - 1;
    maxDepth = Math.max(maxDepth, below);
    for (const c of kids) {
      if (c.count > 0) for (let j = c.ref; j < c.ref + c.count; j++) triangleVisits[j]++;
      else stack.push([c.ref, below]);
    }
  }
  return { nodeVisits, triangleVisits, maxDepth };
}

/** Every child box holds its child node's children's boxes, or its leaf's triangles; sibling leaves hold consecutive triangles. */
function expectBoundsNested(packed: PackedBvh): void {
  const tex = packed.texture.data;
  const inside = (box: { lo: number[]; hi: number[] }, p: ArrayLike<number>) => [0, 1, 2].every((k) => box.lo[k] <= p[k] && p[k] <= box.hi[k]);
  const stack = [BVH_ROOT_NODE];
  while (stack.length) {
    const q = stack.pop()!;
    const pair = children(packed, q);
    for (const c of pair) {
      if (c.count > 0) {
        for (let j = c.ref; j < c.ref + c.count; j++) {
          for (let v = 0; v < 3; v++) {
            const o = (triangleTexel(j) + v) * 4;
            expect(inside(c, tex.subarray(o, o + 3)), `node ${q} holds triangle ${j}`).toBe(true);
          }
        }
      } else {
        for (const g of children(packed, c.ref)) expect(inside(c, g.lo) && inside(c, g.hi), `node ${q} holds node ${c.ref}'s children`).toBe(true);
        stack.push(c.ref);
      }
    }
  }
}

/** Triangle j's 3 texels (12 floats: v0, material, v1, normals texel, v2, mesh). */
const triangleData = (packed: PackedBvh, j: number) => packed.texture.data.subarray(triangleTexel(j) * 4, triangleTexel(j) * 4 + 12);

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
        // No 7-texel read from a triangle's first texel leaves its row, nor overlaps the root (texels 0 .. 6).
        for (let j = 0; j < total; j++) expect(triangleTexel(j) % 2048).toBeLessThanOrEqual(2048 - BVH_NODE_TEXELS);
        for (let j = 0; j < total; j++) expect(triangleTexel(j)).toBeGreaterThanOrEqual(BVH_NODE_TEXELS);
        // No node straddles a row.
        for (const q of walk(packed).nodeVisits.keys()) expect(q % 2048).toBeLessThanOrEqual(2048 - BVH_NODE_TEXELS);
        const { nodeVisits, triangleVisits } = walk(packed);
        // Every node but a leaf root has 2 to 4 children.
        for (const q of nodeVisits.keys()) expect(children(packed, q).length).toBeGreaterThanOrEqual(q === BVH_ROOT_NODE && total === 1 ? 1 : 2);
        expect([...nodeVisits.values()].every((v) => v === 1)).toBe(true);
        expect(nodeVisits.size).toBe(packed.nodeCount);
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
    const tex = packed.texture.data;
    for (let j = 0; j < packed.triangleCount; j++) {
      const tris = triangleData(packed, j);
      const id = packed.triangleOrder[j];
      const mesh = id < 50 ? 0 : 1;
      const local = id - (mesh ? 50 : 0);
      const m = meshes[mesh];
      expect(tris[3]).toBe(m.material);
      expect(tris[11]).toBe(mesh);
      for (let c = 0; c < 3; c++) {
        const v = m.indices[local * 3 + c];
        for (let k = 0; k < 3; k++) expect(tris[c * 4 + k]).toBe(m.positions[v * 3 + k]);
      }
      const normalTexel = tris[7];
      if (!m.normals) expect(normalTexel).toBe(-1);
      else for (let c = 0; c < 3; c++) for (let k = 0; k < 3; k++) expect(tex[(normalTexel + c) * 4 + k]).toBe(m.normals[m.indices[local * 3 + c] * 3 + k]);
    }
  });

  it('packs the corners\' texture coordinates of textured triangles (flat and smooth) and nothing for the others', () => {
    const withUvs = (m: BvhMeshInput, seed: number): BvhMeshInput => {
      const r = random(seed);
      return { ...m, uvs: new Float32Array((m.positions.length / 3) * 2).map(() => r() * 4 - 2) };
    };
    const meshes = [triangleSoup(30, 1, 2, 0, false), withUvs(triangleSoup(40, 2, 2, 0, false), 3), triangleSoup(20, 4, 2, 0, true), withUvs(triangleSoup(50, 5, 2, 0, true), 6)];
    const counts = meshes.map((m) => m.indices.length / 3);
    const packed = build(meshes);
    const tex = packed.texture.data;
    const blocks = new Set<number>();
    for (let j = 0; j < packed.triangleCount; j++) {
      const { mesh, id } = inputTriangle(packed.triangleOrder[j], counts);
      const m = meshes[mesh];
      const a = triangleData(packed, j)[7];
      expect(a >= 0, 'smooth triangles keep their normals at the attributes texel').toBe(!!m.normals);
      if (!m.normals && !m.uvs) expect(a).toBe(-1);
      const k = uvTexel(tex, j);
      expect(k >= 0).toBe(!!m.uvs);
      if (k >= 0) blocks.add(k);
      // Each corner's uv at its own barycentric vertex: (1, 0, 0), (0, 1, 0), (0, 0, 1).
      const corners = [[0, 0], [1, 0], [0, 1]].map(([b1, b2]) => hitUv(packed, { triangle: j, t: 1, b1, b2 }));
      for (let c = 0; c < 3; c++) {
        const v = m.indices[id * 3 + c];
        expect(corners[c]).toEqual(m.uvs ? [m.uvs[v * 2], m.uvs[v * 2 + 1]] : [0, 0]);
      }
    }
    expect(blocks.size, 'a block of its own per textured triangle').toBe(90);
    // Triangles without uvs cost nothing: the nodes follow the attributes (from row 1: 3 texels per smooth triangle, 2 per textured one), from the next row.
    const firstNode = (p: PackedBvh) => Math.min(...[...walk(p).nodeVisits.keys()].filter((q) => q !== BVH_ROOT_NODE));
    expect(firstNode(packed)).toBe(Math.ceil((2048 + 70 * 3 + 90 * 2) / 2048) * 2048);
    expect(firstNode(build(meshes.map((m) => ({ ...m, uvs: null }))))).toBe(Math.ceil((2048 + 70 * 3) / 2048) * 2048);
  });

  it('packs the corners\' vertex colors of colored triangles (flat and smooth, with and without uvs) after their other attributes', () => {
    const withUvs = (m: BvhMeshInput, seed: number): BvhMeshInput => {
      const r = random(seed);
      return { ...m, uvs: new Float32Array((m.positions.length / 3) * 2).map(() => r() * 4 - 2) };
    };
    const withColors = (m: BvhMeshInput, seed: number): BvhMeshInput => {
      const r = random(seed);
      return { ...m, colors: new Float32Array(m.positions.length).map(() => r()) };
    };
    // Every combination of smooth, textured and colored: 8 meshes of 10 + i triangles.
    const meshes = Array.from({ length: 8 }, (_, i) => {
      let m = triangleSoup(10 + i, 10 + i, 2, 0, (i & 1) !== 0);
      if (i & 2) m = withUvs(m, 20 + i);
      if (i & 4) m = withColors(m, 30 + i);
      return m;
    });
    const counts = meshes.map((m) => m.indices.length / 3);
    const packed = build(meshes);
    const tex = packed.texture.data;
    const blocks = new Set<number>();
    for (let j = 0; j < packed.triangleCount; j++) {
      const { mesh, id } = inputTriangle(packed.triangleOrder[j], counts);
      const m = meshes[mesh];
      const k = colorTexel(tex, j);
      expect(k >= 0, `mesh ${mesh}: colors stored exactly for colored meshes`).toBe(!!m.colors);
      if (k >= 0) blocks.add(k);
      const corners = [[0, 0], [1, 0], [0, 1]].map(([b1, b2]) => ({ color: hitColor(packed, { triangle: j, t: 1, b1, b2 }), uv: hitUv(packed, { triangle: j, t: 1, b1, b2 }) }));
      for (let c = 0; c < 3; c++) {
        const v = m.indices[id * 3 + c];
        expect(corners[c].color).toEqual(m.colors ? Array.from(m.colors.subarray(v * 3, v * 3 + 3)) : [1, 1, 1]);
        // The colors leave the uvs as they were ((0, 0) on a colored flat triangle's zero uv block).
        expect(corners[c].uv).toEqual(m.uvs ? [m.uvs[v * 2], m.uvs[v * 2 + 1]] : [0, 0]);
        if (m.normals) for (let q = 0; q < 3; q++) expect(tex[(triangleData(packed, j)[7] + c) * 4 + q]).toBe(m.normals[v * 3 + q]);
      }
    }
    const colored = counts.filter((_, i) => i & 4).reduce((a, b) => a + b, 0);
    expect(blocks.size, 'a color block of its own per colored triangle').toBe(colored);
    // Texels per triangle: 3 normals (smooth), 2 uvs (textured, or flat and colored), 3 colors (colored).
    const texels = meshes.reduce((sum, m, i) => sum + counts[i] * ((m.normals ? 3 : 0) + (m.uvs || (m.colors && !m.normals) ? 2 : 0) + (m.colors ? 3 : 0)), 0);
    const firstNode = (p: PackedBvh) => Math.min(...[...walk(p).nodeVisits.keys()].filter((q) => q !== BVH_ROOT_NODE));
    expect(firstNode(packed)).toBe(Math.ceil((2048 + texels) / 2048) * 2048);
    // Without colors the layout is the uncolored one: nothing for them.
    const plain = meshes.map((m) => ({ ...m, colors: null }));
    const plainTexels = plain.reduce((sum, m, i) => sum + counts[i] * ((m.normals ? 3 : 0) + (m.uvs ? 2 : 0)), 0);
    expect(firstNode(build(plain))).toBe(Math.ceil((2048 + plainTexels) / 2048) * 2048);
  });

  it('the triangle limits are the most whose texels end below 2^24, with and without vertex colors', () => {
    // Triangles 681 to a 2048-texel row (3 texels each), then 5 attribute texels each (3 normals, 2 uvs), 8 with colors (3 more).
    const end = (n: number, attributes: number) => Math.ceil((n + 3) / 681) * 2048 + attributes * n;
    for (const [limit, attributes] of [[MAX_TRIANGLES, 5], [MAX_COLORED_TRIANGLES, 8]]) {
      expect(end(limit, attributes)).toBeLessThanOrEqual(2 ** 24);
      expect(end(limit + 1, attributes)).toBeGreaterThan(2 ** 24);
    }
    expect(MAX_TRIANGLES).toBe(2_095_104);
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
      expect(packed.depth).toBeLessThanOrEqual(MAX_BVH_DEPTH);
      expect(maxDepth).toBeLessThanOrEqual(MAX_WIDE_STACK);
      expect(packed.stackEntries).toBe(maxDepth);
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
            const tris = triangleData(packed, Math.floor(r() * packed.triangleCount));
            dir = [0, 1, 2].map((k) => (tris[k] + tris[4 + k] + tris[8 + k]) / 3 - origin[k]) as unknown as Vec3;
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
        const tris = triangleData(packed, Math.floor(r() * count));
        const origin = vec(r, 3);
        const target = [0, 1, 2].map((k) => (tris[k] + tris[4 + k] + tris[8 + k]) / 3);
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

/** The input mesh that BVH input triangle `input` (the meshes' triangles concatenated) comes from, and its index there. */
function inputTriangle(input: number, counts: number[]): { mesh: number; id: number } {
  let [mesh, id] = [0, input];
  while (id >= counts[mesh]) id -= counts[mesh++];
  return { mesh, id };
}
