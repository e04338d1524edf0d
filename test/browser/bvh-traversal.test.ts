/**
 * The GLSL BVH traversal (src/shaders/scene/bvh.glsl) in the browser,
 * against the TypeScript reference over the same packed textures: the
 * closest hit of random rays over the bunny equals brute force over every
 * triangle, any-hit agrees; closest and any hit equal the TypeScript
 * traversal's on random soups and a sphere, from inside boxes and through
 * shared vertices; the surface's interpolated normal and material
 * are right, and so are the texture coordinates interpolated from the
 * corners' (also in a shared group, in object space); and the watertight
 * test lets no ray aimed exactly at a shared edge or vertex of an icosphere
 * slip through.
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { buildBvh, type BvhMeshInput } from '../../src/render/bvh/build';
import { bvhBounds, packBvh, packBvhGroups, triangleTexel, type PackedBvh } from '../../src/render/bvh/pack';
import { buildAndPack } from '../../src/render/bvh/worker';
import { bruteForce, traverseBvh, type Vec3 } from '../../src/render/bvh/traverse';
import { applyMatrix, inverseAffine, meshToWorldMatrix, transformMesh } from '../../src/scene/mesh/transform';
import { decodeMesh } from '../../src/scene/mesh';
import type { BvhTraceRequest } from '../../src/headless/bvhKernels';
import type { TriangleMesh } from '../../src/scene/types';
import { useRenderSession } from '../support/browser';
import { icosphere } from '../support/icosphere';
import { random, triangleSoup } from '../support/bvhScenes';

const base64 = (data: Float32Array) => Buffer.from(data.buffer, data.byteOffset, data.byteLength).toString('base64');

type Ray = { origin: Vec3; dir: Vec3; tMax: number };

/** Triangle j's 3 texels (12 floats: v0, material, v1, normals texel, v2, mesh). */
const triangleData = (packed: PackedBvh, j: number) => packed.texture.data.subarray(triangleTexel(j) * 4, triangleTexel(j) * 4 + 12);

/** Rays as the kernel reads them (float32), so the TypeScript side uses the same numbers. */
function rayData(rays: Ray[]): Float32Array {
  const data = new Float32Array(rays.length * 8);
  rays.forEach((r, i) => data.set([...r.origin, r.tMax, ...r.dir, 0], i * 8));
  return data;
}

const f32Ray = (data: Float32Array, i: number): Ray => ({
  origin: [data[i * 8], data[i * 8 + 1], data[i * 8 + 2]],
  dir: [data[i * 8 + 4], data[i * 8 + 5], data[i * 8 + 6]],
  tMax: data[i * 8 + 3] >= 3e38 ? Infinity : data[i * 8 + 3],
});

describe('GLSL BVH traversal', () => {
  const session = useRenderSession();

  async function trace(packed: PackedBvh, rays: Float32Array, mode: BvhTraceRequest['mode'], root?: number): Promise<Float32Array> {
    const request: BvhTraceRequest = {
      texture: base64(packed.texture.data),
      rays: base64(rays), width: 64, mode, root,
    };
    const out = await session().page.evaluate((r) => window.pathtraceBvh.trace(r), request);
    const bytes = Buffer.from(out, 'base64');
    return new Float32Array(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength));
  }

  async function bunnyScene() {
    const bunny = await decodeMesh(new Uint8Array(readFileSync(new URL('../fixtures/meshes/bunny.ply', import.meta.url))), 'bunny.ply');
    const meshes: BvhMeshInput[] = [{ ...bunny, material: 3 }, { ...transformMesh(icosphere(2, false), { position: [0.3, 0, 0], scale: 0.02 }), material: 5 }];
    return { meshes, packed: packBvh(buildBvh(meshes), meshes) };
  }

  /** Random rays over the bunny's bounds: half aimed at a random triangle, some with a finite tMax. */
  function randomRays(packed: PackedBvh, count: number, seed: number): Float32Array {
    const r = random(seed);
    const [lo, hi] = bvhBounds(packed);
    const rays: Ray[] = [];
    for (let i = 0; i < count; i++) {
      const origin = [0, 1, 2].map((k) => lo[k] + (r() * 3 - 1) * (hi[k] - lo[k])) as unknown as Vec3;
      let dir = [0, 1, 2].map(() => r() * 2 - 1) as unknown as Vec3;
      if (i % 2 === 0) {
        const tris = triangleData(packed, Math.floor(r() * packed.triangleCount));
        const [b1, b2] = [r() * 0.5, r() * 0.5];
        dir = [0, 1, 2].map((k) => tris[k] * (1 - b1 - b2) + tris[4 + k] * b1 + tris[8 + k] * b2 - origin[k]) as unknown as Vec3;
      }
      rays.push({ origin, dir, tMax: i % 5 === 0 ? r() * 0.2 : 3.4e38 });
    }
    return rayData(rays);
  }

  it('closest hit equals brute force over every triangle (bunny, 4096 random rays)', async () => {
    const { packed } = await bunnyScene();
    const rays = randomRays(packed, 4096, 1);
    const out = await trace(packed, rays, 'closest');
    let hits = 0;
    const mismatches: string[] = [];
    for (let i = 0; i < 4096; i++) {
      const ray = f32Ray(rays, i);
      const expected = bruteForce(packed, ray.origin, ray.dir, ray.tMax);
      const [triangle, t] = out.subarray(i * 4, i * 4 + 2);
      if (expected) hits++;
      const same = expected
        ? triangle >= 0 && Math.abs(t - expected.t) <= 1e-4 * expected.t
        : triangle === -1;
      if (!same) mismatches.push(`ray ${i}: GLSL ${triangle} at ${t}, brute force ${expected?.triangle} at ${expected?.t}`);
      // A different triangle at the same t is a tie on a shared edge; the GLSL's own triangle must be hit there.
      if (same && expected && triangle !== expected.triangle) {
        const own = bruteForceOne(packed, triangle, ray);
        if (own === null || Math.abs(own - t) > 1e-4 * t) mismatches.push(`ray ${i}: GLSL triangle ${triangle} is not hit at ${t}`);
      }
    }
    expect(hits, 'most rays must hit something').toBeGreaterThan(1500);
    expect(mismatches.slice(0, 10)).toEqual([]);
  });

  it('closest hit (triangle and t) and any hit as the TypeScript traversal: random soups whose leaves cross row ends, rays from inside boxes and through shared vertices', async () => {
    // Soups of up to 3000 triangles (some leaves cross the ends of the 681-triangle rows, where the
    // next triangle is on the next row) and an icosphere (shared edges and vertices: rays aimed exactly at its vertices).
    const sphere = transformMesh(icosphere(3, false), { position: [0.2, -0.1, 0.3], rotation: [11, 23, 37] });
    const scenes: BvhMeshInput[][] = [
      [triangleSoup(3000, 21, 2, 0, true)],
      [triangleSoup(700, 22, 1, 0), triangleSoup(1500, 23, 0.05, 1)],
      [{ ...sphere, material: 0 }, triangleSoup(400, 24, 1.5, 1)],
    ];
    const r = random(9);
    for (const [s, meshes] of scenes.entries()) {
      const packed = packBvh(buildBvh(meshes), meshes);
      const [lo, hi] = bvhBounds(packed);
      const inside = () => [0, 1, 2].map((k) => lo[k] + r() * (hi[k] - lo[k])) as unknown as Vec3;
      const rays: Ray[] = [];
      const vertexRays = new Set<number>();
      for (let i = 0; i < 2048; i++) {
        // Origins inside the root's boxes (and so inside many child boxes).
        // Soups: a point inside a random triangle; the sphere scene: a vertex of the sphere (shared by 5 or 6
        // triangles) from near its centre, so the ray crosses it there: some triangle at the vertex is hit.
        const atVertex = s === 2 && i % 3 === 0;
        const origin = atVertex ? ([0.2 + (r() - 0.5) * 0.2, -0.1 + (r() - 0.5) * 0.2, 0.3 + (r() - 0.5) * 0.2] as Vec3) : inside();
        if (atVertex) vertexRays.add(i);
        const tris = triangleData(packed, Math.floor(r() * packed.triangleCount));
        const [b1, b2] = [0.1 + r() * 0.4, 0.1 + r() * 0.4];
        const v = Math.floor(r() * (sphere.positions.length / 3));
        const target = i % 3 > 0 ? inside() : atVertex ? Array.from(sphere.positions.subarray(v * 3, v * 3 + 3)) : [0, 1, 2].map((k) => tris[k] * (1 - b1 - b2) + tris[4 + k] * b1 + tris[8 + k] * b2);
        rays.push({ origin, dir: [0, 1, 2].map((k) => target[k] - origin[k]) as unknown as Vec3, tMax: i % 4 === 1 && !atVertex ? r() * 0.5 : 3.4e38 });
      }
      const data = rayData(rays);
      const [closest, any] = [await trace(packed, data, 'closest'), await trace(packed, data, 'any')];
      const wrong: string[] = [];
      let hits = 0;
      for (let i = 0; i < rays.length; i++) {
        const ray = f32Ray(data, i);
        const expected = traverseBvh(packed, ray.origin, ray.dir, ray.tMax);
        const [triangle, t] = closest.subarray(i * 4, i * 4 + 2);
        if (expected) hits++;
        if ((any[i * 4] === 1) !== (expected !== null)) wrong.push(`scene ${s} ray ${i}: any hit ${any[i * 4]}, TypeScript ${expected?.t}`);
        if (!expected) {
          if (triangle !== -1) wrong.push(`scene ${s} ray ${i}: GLSL hits ${triangle}, TypeScript nothing`);
          continue;
        }
        // t to float precision (origins close to a triangle: t near 0 in the ray's units, which are the scene's).
        const close = (a: number, b: number) => Math.abs(a - b) <= 1e-4 * Math.max(b, 0.01);
        if (triangle < 0 || !close(t, expected.t)) wrong.push(`scene ${s} ray ${i}: GLSL ${triangle} at ${t}, TypeScript ${expected.triangle} at ${expected.t}`);
        // Another triangle only at a tie (a shared edge or vertex): the GLSL's own must be hit there.
        // (At a vertex the tie is exact: rounding decides which of its triangles, in float or double.)
        else if (triangle !== expected.triangle && !vertexRays.has(i) && !close(bruteForceOne(packed, triangle, ray) ?? -1, t)) wrong.push(`scene ${s} ray ${i}: GLSL triangle ${triangle} is not hit at ${t}`);
      }
      expect(hits, `scene ${s}: most rays hit`).toBeGreaterThan(1000);
      expect(wrong.slice(0, 10)).toEqual([]);
    }
  });

  it('any-hit agrees with brute force on whether anything is hit before tMax', async () => {
    const { packed } = await bunnyScene();
    const rays = randomRays(packed, 4096, 2);
    const out = await trace(packed, rays, 'any');
    const wrong: number[] = [];
    for (let i = 0; i < 4096; i++) {
      const ray = f32Ray(rays, i);
      if ((out[i * 4] === 1) !== (bruteForce(packed, ray.origin, ray.dir, ray.tMax) !== null)) wrong.push(i);
    }
    expect(wrong).toEqual([]);
  });

  it('the surface: interpolated vertex normal (smooth bunny), face normal (flat sphere), material', async () => {
    const { packed } = await bunnyScene();
    const rays = randomRays(packed, 4096, 3);
    const hits = await trace(packed, rays, 'closest');
    const surfaces = await trace(packed, rays, 'surface');
    const tex = packed.texture.data;
    let checked = 0;
    for (let i = 0; i < 4096; i++) {
      const j = hits[i * 4];
      if (j < 0) continue;
      const tris = triangleData(packed, j);
      const [b1, b2] = [hits[i * 4 + 2], hits[i * 4 + 3]];
      const v = (c: number, k: number) => tris[c * 4 + k];
      const normalTexel = tris[7];
      let n: number[];
      if (normalTexel >= 0) {
        n = [0, 1, 2].map((k) => (1 - b1 - b2) * tex[normalTexel * 4 + k] + b1 * tex[(normalTexel + 1) * 4 + k] + b2 * tex[(normalTexel + 2) * 4 + k]);
      } else {
        const e1 = [0, 1, 2].map((k) => v(1, k) - v(0, k));
        const e2 = [0, 1, 2].map((k) => v(2, k) - v(0, k));
        n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
      }
      const length = Math.hypot(...n);
      for (let k = 0; k < 3; k++) expect(Math.abs(surfaces[i * 4 + k] - n[k] / length)).toBeLessThan(1e-4);
      expect(surfaces[i * 4 + 3]).toBe(tris[3]);
      checked++;
    }
    expect(checked).toBeGreaterThan(1500);
  });

  it('texture coordinates: the corners\' interpolated at the hit (smooth and flat textured meshes, one without, a shared group in object space)', async () => {
    const uvbox = await decodeMesh(new Uint8Array(readFileSync(new URL('../fixtures/meshes/uvbox.obj', import.meta.url))), 'uvbox.obj');
    expect(uvbox.uvs && uvbox.normals).toBeTruthy();
    // uv = a function of the object-space position, different per mesh: a mixed-up corner or mesh shows.
    const mapped = (mesh: TriangleMesh, f: (p: number[]) => [number, number]): TriangleMesh => {
      const uvs = new Float32Array((mesh.positions.length / 3) * 2);
      for (let v = 0; v < mesh.positions.length / 3; v++) uvs.set(f([0, 1, 2].map((k) => mesh.positions[v * 3 + k])), v * 2);
      return { ...mesh, uvs };
    };
    const world: BvhMeshInput[] = [
      { ...transformMesh(uvbox, { position: [0, 0, 0], rotation: [10, 20, 30] }), material: 0, mesh: 0 }, // smooth, the file's uvs
      { ...transformMesh({ ...uvbox, normals: null }, { position: [1.5, 0.2, 0], rotation: [-30, 40, 5] }), material: 0, mesh: 1 }, // flat, the file's uvs
      { ...mapped(transformMesh(icosphere(3, true), { position: [-1.5, 0, 0.3], scale: 0.6 }), (p) => [0.3 + 0.7 * p[0] - 0.2 * p[2], 1.3 * p[1] - 0.1]), material: 0, mesh: 2 },
      { ...transformMesh(icosphere(2, false), { position: [0, 1.5, 0], scale: 0.5 }), material: 0, mesh: 3 }, // no uvs: (0, 0)
    ];
    const shared: BvhMeshInput[] = [{ ...mapped(icosphere(3, true), (p) => [2 * p[0] + p[1], 0.5 - p[2]]), material: 0, mesh: -1 }];
    const groups = [world, shared];
    const packed = packBvhGroups(groups.map((meshes) => ({ bvh: buildBvh(meshes), meshes })));
    const worldTriangles = world.reduce((n, m) => n + m.indices.length / 3, 0);
    // The input triangle of BVH triangle j: its corners' uvs (null without) from the input meshes, not the texture.
    const inputs = groups.flat();
    const cornerUvs = (j: number): number[][] | null => {
      let id = packed.triangleOrder[j];
      let m = 0;
      while (id >= inputs[m].indices.length / 3) id -= inputs[m++].indices.length / 3;
      const { uvs, indices } = inputs[m];
      return uvs ? [0, 1, 2].map((c) => [uvs[indices[id * 3 + c] * 2], uvs[indices[id * 3 + c] * 2 + 1]]) : null;
    };
    // An instance's object-to-world transform: rays are taken into object space as scene/instances.glsl does.
    const toWorld = meshToWorldMatrix({ position: [0.4, -2, 1], rotation: [25, -60, 15], scale: 1.7 });
    const toObject = inverseAffine(toWorld);
    const r = random(11);
    const rays = (first: number, count: number, objectSpace: boolean): Ray[] =>
      Array.from({ length: 2048 }, () => {
        const tris = triangleData(packed, first + Math.floor(r() * count));
        const [b1, b2] = [r() * 0.6, r() * 0.4];
        const target = [0, 1, 2].map((k) => tris[k] * (1 - b1 - b2) + tris[4 + k] * b1 + tris[8 + k] * b2);
        const origin = target.map((x) => x + (r() * 2 - 1) * 4);
        if (!objectSpace) return { origin: origin as unknown as Vec3, dir: target.map((x, k) => x - origin[k]) as unknown as Vec3, tMax: 3.4e38 };
        // A world ray at the instance's target, taken into object space.
        const [oo, tt] = [origin, target].map((p) => applyMatrix(toObject, applyMatrix(toWorld, p, null).positions, null).positions);
        return { origin: [oo[0], oo[1], oo[2]], dir: [tt[0] - oo[0], tt[1] - oo[1], tt[2] - oo[2]], tMax: 3.4e38 };
      });
    let [textured, untextured] = [0, 0];
    for (const [group, objectSpace] of [[0, false], [1, true]] as const) {
      const data = rayData(group === 0 ? rays(0, worldTriangles, false) : rays(worldTriangles, packed.triangleCount - worldTriangles, true));
      const out = await trace(packed, data, 'uv', packed.roots[group]);
      const wrong: string[] = [];
      for (let i = 0; i < data.length / 8; i++) {
        const ray = f32Ray(data, i);
        const expected = traverseBvh(packed, ray.origin, ray.dir, Infinity, false, undefined, packed.roots[group]);
        const [u, v, triangle] = out.subarray(i * 4, i * 4 + 3);
        if (!expected) {
          if (triangle !== -1) wrong.push(`ray ${i}: GLSL hits ${triangle}, TypeScript nothing`);
          continue;
        }
        // The GLSL's own triangle (a tie on a shared edge may pick the neighbour), its barycentrics in TypeScript.
        const hit = triangle >= 0 ? bruteForce(packed, ray.origin, ray.dir, Infinity, triangle) : null;
        if (!hit || Math.abs(hit.t - expected.t) > 1e-4 * expected.t) {
          wrong.push(`ray ${i}: GLSL triangle ${triangle} is not hit`);
          continue;
        }
        const corners = cornerUvs(triangle);
        const b = [1 - hit.b1 - hit.b2, hit.b1, hit.b2];
        const uv = corners ? [0, 1].map((k) => b[0] * corners[0][k] + b[1] * corners[1][k] + b[2] * corners[2][k]) : [0, 0];
        if (corners) textured++;
        else untextured++;
        if (Math.abs(u - uv[0]) > 2e-4 || Math.abs(v - uv[1]) > 2e-4) wrong.push(`ray ${i} (group ${group}, triangle ${triangle}): GLSL uv (${u}, ${v}), expected (${uv[0]}, ${uv[1]})`);
      }
      expect(wrong.slice(0, 10)).toEqual([]);
    }
    expect(textured, 'hits on textured triangles').toBeGreaterThan(3000);
    expect(untextured, 'hits on the mesh without uvs').toBeGreaterThan(100);
  });

  it('the page builds the same BVH in its Web Worker as Node does', async () => {
    const mesh = transformMesh(icosphere(4, false), { rotation: [10, 20, 30] });
    const b64 = (a: Float32Array | Uint32Array) => Buffer.from(a.buffer, a.byteOffset, a.byteLength).toString('base64');
    const built = await session().page.evaluate(([p, i]) => window.pathtraceBvh.buildInWorker(p, null, i, 2), [b64(mesh.positions), b64(mesh.indices)] as const);
    const expected = buildAndPack([{ ...mesh, material: 2 }]);
    expect(built.depth).toBe(expected.depth);
    expect(built.texture).toBe(b64(expected.texture.data));
    // With texture coordinates, flat and smooth.
    const uvs = new Float32Array((mesh.positions.length / 3) * 2).map((_, i) => mesh.positions[Math.floor(i / 2) * 3 + (i % 2)] * 0.5 + 0.25);
    for (const normals of [null, transformMesh(icosphere(4, true), { rotation: [10, 20, 30] }).normals!]) {
      const withUvs = await session().page.evaluate(([p, n, i, t]) => window.pathtraceBvh.buildInWorker(p, n, i, 2, false, t), [b64(mesh.positions), normals && b64(normals), b64(mesh.indices), b64(uvs)] as const);
      expect(withUvs.texture).toBe(b64(buildAndPack([{ ...mesh, normals, uvs, material: 2 }]).texture.data));
    }
  });

  it('a 328k-triangle smooth icosphere (its texture spans 3 layers): hits and normals as in TypeScript', async () => {
    const mesh = transformMesh(icosphere(7, true), { rotation: [10, 20, 30] });
    const b64 = (a: Float32Array | Uint32Array) => Buffer.from(a.buffer, a.byteOffset, a.byteLength).toString('base64');
    const built = await session().page.evaluate(([p, n, i]) => window.pathtraceBvh.buildInWorker(p, n, i, 4, true), [b64(mesh.positions), b64(mesh.normals!), b64(mesh.indices)] as const);
    const packed = buildAndPack([{ ...mesh, material: 4 }]);
    expect(built.depth).toBe(packed.depth);
    expect(packed.texture.layers).toBe(3);
    const r = random(5);
    const rays: Ray[] = [];
    for (let i = 0; i < 4096; i++) {
      const origin = [0, 1, 2].map(() => (r() * 2 - 1) * 3) as unknown as Vec3;
      rays.push({ origin, dir: [0, 1, 2].map((k) => (r() - 0.5) * 0.5 - origin[k]) as unknown as Vec3, tMax: 3.4e38 });
    }
    const data = rayData(rays);
    const request = (mode: BvhTraceRequest['mode']): BvhTraceRequest => ({ texture: '', rays: base64(data), width: 64, mode });
    const hits = await session().page.evaluate((q) => window.pathtraceBvh.trace(q), request('closest')).then(floats);
    const surfaces = await session().page.evaluate((q) => window.pathtraceBvh.trace(q), request('surface')).then(floats);
    const tex = packed.texture.data;
    let laterLayers = 0;
    for (let i = 0; i < rays.length; i++) {
      const j = hits[i * 4];
      expect(j, `ray ${i} hits`).toBeGreaterThanOrEqual(0);
      const tris = triangleData(packed, j);
      const expected = traverseBvh(packed, f32Ray(data, i).origin, f32Ray(data, i).dir, Infinity)!;
      expect(Math.abs(hits[i * 4 + 1] - expected.t)).toBeLessThanOrEqual(1e-4 * expected.t);
      const [b1, b2] = [hits[i * 4 + 2], hits[i * 4 + 3]];
      const k = tris[7];
      if (k >= 2 ** 20) laterLayers++; // normals start in layer 0 and end in layer 1
      const n = [0, 1, 2].map((c) => (1 - b1 - b2) * tex[k * 4 + c] + b1 * tex[(k + 1) * 4 + c] + b2 * tex[(k + 2) * 4 + c]);
      const length = Math.hypot(...n);
      for (let c = 0; c < 3; c++) expect(Math.abs(surfaces[i * 4 + c] - n[c] / length)).toBeLessThan(1e-4);
      expect(surfaces[i * 4 + 3]).toBe(4);
    }
    expect(laterLayers, 'normals read from layer 1').toBeGreaterThan(1000);
  });

  it('watertight: rays crossing an icosphere exactly at shared edges and vertices always hit', async () => {
    // An off-centre, rotated, unevenly scaled sphere, so no coordinate is round.
    const mesh = transformMesh(icosphere(3, false), { position: [0.37, -1.21, 0.93], rotation: [17, 41, -73], scale: [1.3, 0.7, 1.1] });
    const meshes = [{ ...mesh, material: 0 }];
    const packed = packBvh(buildBvh(meshes), meshes);
    const p = mesh.positions;
    const vertex = (v: number) => [p[v * 3], p[v * 3 + 1], p[v * 3 + 2]];
    const faceNormal = (t: number) => {
      const [a, b, c] = [0, 1, 2].map((k) => vertex(mesh.indices[t * 3 + k]));
      const e1 = [0, 1, 2].map((k) => b[k] - a[k]);
      const e2 = [0, 1, 2].map((k) => c[k] - a[k]);
      const n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
      return n.map((x) => x / Math.hypot(...n));
    };
    // Targets: every vertex and two points on every edge, with the faces that share them.
    const targets: { point: number[]; faces: number[] }[] = [];
    const facesOf = new Map<number, number[]>();
    const edges = new Map<string, { a: number; b: number; faces: number[] }>();
    for (let t = 0; t < mesh.indices.length / 3; t++) {
      for (let e = 0; e < 3; e++) {
        const a = mesh.indices[t * 3 + e];
        const b = mesh.indices[t * 3 + ((e + 1) % 3)];
        facesOf.set(a, [...(facesOf.get(a) ?? []), t]);
        const key = a < b ? `${a},${b}` : `${b},${a}`;
        const edge = edges.get(key) ?? { a, b, faces: [] };
        edge.faces.push(t);
        edges.set(key, edge);
      }
    }
    for (const [v, faces] of facesOf) targets.push({ point: vertex(v), faces });
    for (const { a, b, faces } of edges.values()) {
      expect(faces.length, 'closed mesh: two faces per edge').toBe(2);
      for (const s of [0.5, 0.25]) targets.push({ point: [0, 1, 2].map((k) => Math.fround(p[a * 3 + k] * (1 - s) + p[b * 3 + k] * s)), faces });
    }
    const r = random(7);
    const rays: Ray[] = [];
    let tangent = 0;
    for (const { point, faces } of targets) {
      // From outside (random far points) and from inside (near the centre).
      for (const scale of [6, 0.2]) {
        const origin = [0.37 + (r() * 2 - 1) * scale, -1.21 + (r() * 2 - 1) * scale, 0.93 + (r() * 2 - 1) * scale] as unknown as Vec3;
        const dir = [0, 1, 2].map((k) => point[k] - origin[k]) as unknown as Vec3;
        // A ray that only grazes the surface there (the faces around the point
        // face it from both sides, or edge-on) may rightly miss: it touches a
        // silhouette, and rounding the target moves it off. Only crossings count.
        const cosines = faces.map((t) => faceNormal(t).reduce((sum, n, k) => sum + n * dir[k], 0) / Math.hypot(...dir));
        if (!(cosines.every((c) => c > 0.02) || cosines.every((c) => c < -0.02))) {
          tangent++;
          continue;
        }
        rays.push({ origin, dir, tMax: 3.4e38 });
      }
    }
    const data = rayData(rays);
    const out = await trace(packed, data, 'closest');
    const missed: number[] = [];
    for (let i = 0; i < rays.length; i++) if (out[i * 4] < 0) missed.push(i);
    expect(rays.length).toBeGreaterThan(5000);
    expect(tangent).toBeLessThan(rays.length / 10);
    expect(missed.length, `missed rays (first: ${missed.slice(0, 5)})`).toBe(0);
  });
});

function floats(text: string): Float32Array {
  const bytes = Buffer.from(text, 'base64');
  return new Float32Array(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength));
}

/** t of `ray` on triangle j alone, or null. */
function bruteForceOne(packed: PackedBvh, j: number, ray: Ray): number | null {
  const hit = bruteForce(packed, ray.origin, ray.dir, ray.tMax, j);
  return hit?.t ?? null;
}
