/**
 * Instancing (src/render/bvh/groups.ts): which meshes share one stored copy
 * of a file's triangles, that several BVH groups packed into one texture are
 * each a complete BVH from their own root, and that a query through an
 * instance (the ray taken into object space, as scene/instances.glsl does)
 * finds what brute force finds over the mesh copied into world space.
 */
import { readFileSync } from 'node:fs';
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { groupMeshes, INSTANCE_MIN_SAVED_TRIANGLES, MAX_INSTANCES, storedTriangles } from '../../src/render/bvh/groups';
import { buildBvh, type BvhMeshInput } from '../../src/render/bvh/build';
import { nodeChildren, packBvh, packBvhGroups, triangleAt, type PackedBvh } from '../../src/render/bvh/pack';
import { bruteForce, traverseBvh, type Vec3 } from '../../src/render/bvh/traverse';
import { buildAndPackGroups } from '../../src/render/bvh/worker';
import { bvhInputs } from '../../src/render/geometry/world';
import { decodeMesh, meshToWorldMatrix, transformMesh, type MeshTransform } from '../../src/scene/mesh';
import type { Material, Mesh, Scene, TriangleMesh } from '../../src/scene/types';
import { parseSceneText } from '../../src/scene/schema';
import { random, triangleSoup } from '../support/bvhScenes';
import { icosphere } from '../support/icosphere';

const white: Material = { type: 'standard', color: [1, 1, 1], roughness: 1 };
const glowing: Material = { ...white, emission: { color: [1, 1, 1], intensity: 2 } };
const mesh = (file: string, material: Material = white): Mesh => ({ file, material, position: [0, 0, 0], rotation: [0, 0, 0], scale: [1, 1, 1] });
const CAMERA = { position: [0, 0, 5], target: [0, 0, 0], fov: 40 };
const sceneWith = (meshes: Mesh[]): Scene => ({ ...parseSceneText(JSON.stringify({ version: 2, camera: CAMERA })), meshes });

/** Every file this big: any file named twice saves enough to be instanced. */
const big = () => INSTANCE_MIN_SAVED_TRIANGLES;

describe('grouping meshes for instancing', () => {
  it('shares a file named by several non-emissive meshes; copies the rest', () => {
    const scene = sceneWith([mesh('a'), mesh('b'), mesh('a'), mesh('c'), mesh('a'), mesh('b', glowing), mesh('b')]);
    // b is named three times, but once by an emitter: that one is copied, the other two share.
    expect(groupMeshes(scene, big)).toEqual({ world: [3, 5], shared: [[0, 2, 4], [1, 6]] });
  });

  it('emissive meshes are never instanced; a file named once is copied', () => {
    expect(groupMeshes(sceneWith([mesh('a', glowing), mesh('a', glowing), mesh('b')]), big)).toEqual({ world: [0, 1, 2], shared: [] });
  });

  it('copies a file whose copies would add fewer than INSTANCE_MIN_SAVED_TRIANGLES triangles (faster)', () => {
    const half = () => INSTANCE_MIN_SAVED_TRIANGLES / 2;
    expect(groupMeshes(sceneWith([mesh('a'), mesh('a')]), half).shared).toEqual([]);
    expect(groupMeshes(sceneWith([mesh('a'), mesh('a'), mesh('a')]), half).shared).toEqual([[0, 1, 2]]);
    expect(groupMeshes(sceneWith([mesh('a'), mesh('a')]), () => INSTANCE_MIN_SAVED_TRIANGLES - 1).shared).toEqual([]);
  });

  it('keeps the instance loop within MAX_INSTANCES records, the world group counted', () => {
    const many = sceneWith([...Array.from({ length: MAX_INSTANCES }, () => mesh('a')), mesh('b'), mesh('c'), mesh('c')]);
    const { world, shared } = groupMeshes(many, big);
    // MAX_INSTANCES copies of a plus the world group would need MAX_INSTANCES + 1 records: a is copied, c shared.
    expect(shared).toEqual([[MAX_INSTANCES + 1, MAX_INSTANCES + 2]]);
    expect(world).toEqual([...Array.from({ length: MAX_INSTANCES }, (_, i) => i), MAX_INSTANCES]);
    fc.assert(
      fc.property(fc.array(fc.record({ file: fc.constantFrom('a', 'b', 'c', 'd'), glows: fc.boolean() }), { maxLength: 30 }), (spec) => {
        const scene = sceneWith(spec.map((m) => mesh(m.file, m.glows ? glowing : white)));
        const groups = groupMeshes(scene, big);
        const records = groups.shared.flat().length + (groups.world.length > 0 && groups.shared.length > 0 ? 1 : 0);
        expect(records).toBeLessThanOrEqual(MAX_INSTANCES);
        expect([...groups.world, ...groups.shared.flat()].sort((x, y) => x - y)).toEqual(spec.map((_, i) => i));
        for (const users of groups.shared) {
          expect(users.length).toBeGreaterThanOrEqual(2);
          expect(new Set(users.map((i) => scene.meshes[i].file)).size).toBe(1);
          expect(users.every((i) => !spec[i].glows)).toBe(true);
        }
      }),
    );
  });

  it('counts an instanced file once against the triangle limit', () => {
    const scene = sceneWith([mesh('a'), mesh('a'), mesh('b'), mesh('a', glowing), mesh('b')]);
    const count = (f: string) => ({ a: INSTANCE_MIN_SAVED_TRIANGLES, b: 10 })[f as 'a' | 'b'];
    // a: once for its two instances, once more for the emitter's copy; b is copied (too small to instance).
    expect(storedTriangles(scene, count)).toBe(2 * INSTANCE_MIN_SAVED_TRIANGLES + 20);
  });
});

/** The group's triangles and nodes are all reachable from its root, and no other group's. */
function trianglesUnder(packed: PackedBvh, root: number): Set<number> {
  const d = packed.texture.data;
  const found = new Set<number>();
  const stack = [root];
  while (stack.length) {
    const q = stack.pop()!;
    for (const child of nodeChildren(d, q)) {
      if (!child) continue;
      const { ref, count } = child;
      if (count > 0) for (let t = triangleAt(ref); t < triangleAt(ref) + count; t++) found.add(t);
      else stack.push(ref);
    }
  }
  return found;
}

describe('several BVH groups in one texture', () => {
  it('each root reaches exactly its group\'s triangles; one group packs as packBvh does', () => {
    const groups = [[triangleSoup(700, 1, 3, 2, true), triangleSoup(90, 2, 3, 5, false)], [triangleSoup(1, 3, 1, -1)], [triangleSoup(2000, 4, 1, -1, true)]];
    const packed = buildAndPackGroups(groups);
    const counts = groups.map((g) => g.reduce((n, m) => n + m.indices.length / 3, 0));
    expect(packed.roots).toHaveLength(3);
    let first = 0;
    groups.forEach((_, g) => {
      const under = trianglesUnder(packed, packed.roots[g]);
      expect([...under].sort((a, b) => a - b)).toEqual(Array.from({ length: counts[g] }, (_, j) => first + j));
      first += counts[g];
    });
    const single = [triangleSoup(300, 9, 2, 1, true)];
    expect(packBvhGroups([{ bvh: buildBvh(single), meshes: single }]).texture.data).toEqual(packBvh(buildBvh(single), single).texture.data);
  });
});

/** The ray through the inverse of `toWorld` (column-major affine), as instances.glsl takes it: t is unchanged. */
function toObject(toWorld: Float64Array, origin: Vec3, dir: Vec3): [Vec3, Vec3] {
  const a = [0, 1, 2].map((r) => [0, 1, 2].map((c) => toWorld[c * 4 + r]));
  const det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  const inv = [0, 1, 2].map((r) => [0, 1, 2].map((c) => {
    const rows = [0, 1, 2].filter((k) => k !== c);
    const cols = [0, 1, 2].filter((k) => k !== r);
    const minor = a[rows[0]][cols[0]] * a[rows[1]][cols[1]] - a[rows[0]][cols[1]] * a[rows[1]][cols[0]];
    return ((r + c) % 2 ? -minor : minor) / det;
  }));
  const p = [0, 1, 2].map((k) => origin[k] - toWorld[12 + k]);
  const apply = (v: number[]) => [0, 1, 2].map((r) => inv[r][0] * v[0] + inv[r][1] * v[1] + inv[r][2] * v[2]) as unknown as Vec3;
  return [apply(p), apply([...dir])];
}

const transformArb = fc.record({
  position: fc.tuple(fc.double({ min: -5, max: 5, noNaN: true }), fc.double({ min: -5, max: 5, noNaN: true }), fc.double({ min: -5, max: 5, noNaN: true })),
  rotation: fc.tuple(fc.double({ min: -180, max: 180, noNaN: true }), fc.double({ min: -180, max: 180, noNaN: true }), fc.double({ min: -180, max: 180, noNaN: true })),
  scale: fc.tuple(fc.double({ min: 0.05, max: 20, noNaN: true }), fc.double({ min: 0.05, max: 20, noNaN: true }), fc.double({ min: 0.05, max: 20, noNaN: true })),
});

describe('queries through an instance', async () => {
  const bunny = await decodeMesh(new Uint8Array(readFileSync(new URL('../fixtures/meshes/bunny.ply', import.meta.url))), 'bunny.ply');

  it('find the hit brute force finds on the world-space copy (rays aimed inside triangles)', () => {
    const shapes: TriangleMesh[] = [bunny, icosphere(2, true)];
    fc.assert(
      fc.property(transformArb, fc.nat(), fc.constantFrom(0, 1), (transform: MeshTransform, seed, which) => {
        const data = shapes[which];
        const shared = buildAndPackGroups([[triangleSoup(50, seed, 3, 0)], [{ ...data, material: 0, mesh: -1 }]]);
        const toWorld = meshToWorldMatrix(transform);
        const copy: BvhMeshInput = { ...transformMesh(data, transform), material: 0 };
        const world = packBvh(buildBvh([copy]), [copy]);
        const r = random(seed);
        for (let i = 0; i < 30; i++) {
          // A point well inside a random triangle of the copy, from a random origin around it.
          const t = Math.floor(r() * copy.indices.length / 3);
          const [b1, b2] = [0.1 + 0.35 * r(), 0.1 + 0.35 * r()];
          const target = [0, 1, 2].map((k) => {
            const v = (c: number) => copy.positions[copy.indices[t * 3 + c] * 3 + k];
            return (1 - b1 - b2) * v(0) + b1 * v(1) + b2 * v(2);
          });
          const origin = [0, 1, 2].map((k) => target[k] + (r() * 2 - 1) * 50) as unknown as Vec3;
          const dir = [0, 1, 2].map((k) => target[k] - origin[k]) as unknown as Vec3;
          const expected = bruteForce(world, origin, dir, Infinity);
          expect(expected, 'the copy is hit').not.toBeNull();
          const [o, d] = toObject(toWorld, origin, dir);
          const found = traverseBvh(shared, o, d, Infinity, false, undefined, shared.roots[1]);
          expect(found, 'the instance is hit').not.toBeNull();
          // Same t up to the transform's rounding (float32 vertices, a ray through a 3x4 matrix).
          expect(Math.abs(found!.t - expected!.t)).toBeLessThan(1e-4 * expected!.t + 1e-6);
          expect(traverseBvh(shared, o, d, Infinity, true, undefined, shared.roots[1])).not.toBeNull();
          // The other group's root does not see the instance's triangles.
          const other = traverseBvh(shared, o, d, Infinity, false, undefined, shared.roots[0]);
          if (other) expect(other.triangle).toBeLessThan(50);
        }
      }),
      { numRuns: 40 },
    );
  });

  it('a file named by three meshes is stored once, when big enough; a small one is copied', () => {
    const scene = parseSceneText(
      JSON.stringify({
        version: 2,
        camera: CAMERA,
        meshes: [0, 1, 2].map((i) => ({ file: 'model.ply', position: [i, 0, 0], scale: 0.1 + i * 0.05, material: { color: [0.5, 0.5, 0.5], roughness: 1 } })),
      }),
    );
    const dense = icosphere(6, true); // 81920 triangles: two more copies would add 163840
    const stored = (data: TriangleMesh) => buildAndPackGroups(bvhInputs(scene, { maps: new Map(), meshes: new Map([['model.ply', data]]) }));
    expect(stored(dense).triangleCount).toBe(dense.indices.length / 3);
    expect(stored(bunny).triangleCount).toBe(3 * (bunny.indices.length / 3));
  });

  it("texture coordinates reach the BVH's inputs: a copy's and a shared file's", () => {
    const withUvs = (m: TriangleMesh): TriangleMesh => ({ ...m, uvs: new Float32Array((m.positions.length / 3) * 2).map((_, i) => i * 1e-3) });
    const [dense, small] = [withUvs(icosphere(6, true)), withUvs(icosphere(1, false))];
    const scene = parseSceneText(
      JSON.stringify({
        version: 2,
        camera: CAMERA,
        meshes: [...[0, 1, 2].map((i) => ({ file: 'dense.ply', position: [i, 0, 0] })), { file: 'small.ply', position: [0, 2, 0] }].map((m) => ({ ...m, material: { color: [0.5, 0.5, 0.5], roughness: 1 } })),
      }),
    );
    const [copies, shared] = bvhInputs(scene, { maps: new Map(), meshes: new Map([['dense.ply', dense], ['small.ply', small]]) });
    expect(copies.map((m) => m.uvs)).toEqual([small.uvs]);
    expect(shared.map((m) => m.uvs)).toEqual([dense.uvs]);
  });

  it("the BVH's texels depend on the meshes' geometry only: not on spheres, lights, the ground or materials", () => {
    const meshes: Mesh[] = [mesh('a'), { ...mesh('b'), position: [1, 0, 0] }];
    const plain = sceneWith(meshes);
    const assets = { maps: new Map(), meshes: new Map([['a', bunny], ['b', icosphere(2, false)]]) };
    const texels = (scene: Scene) => buildAndPackGroups(bvhInputs(scene, assets)).texture.data;
    const edited: Scene = {
      ...plain,
      spheres: [{ center: [0, 2, 0], radius: 0.5, material: white }],
      lights: [{ type: 'sphere', position: [0, 3, 0], radius: 0.2, color: [1, 1, 1], intensity: 5 }],
      ground: plain.ground ? null : { height: -1, material: white },
      meshes: meshes.map((m, i) => ({ ...m, material: { type: 'standard', color: [0.2 * i, 0.5, 0.5], roughness: 0.3 } })),
    };
    expect(texels(edited)).toEqual(texels(plain));
  });
});
