/**
 * Tangent frames for normal maps (scene format, "Meshes in version 3": glTF's
 * rule, bitangent = cross(n, tangent) * w up the image, toward decreasing v):
 * MikkTSpace on planar quads with affine coordinates gives dp/du and the
 * right w, mirrored charts included (where Mitsuba's cross(n, dp/du) would
 * point down the image); a glTF's TANGENT is read as given, through its
 * node's matrix (a mirroring one turns w over); no coordinates, no frame;
 * curved and degenerate meshes give unit tangents orthogonal to the normal,
 * never NaN.
 */
import { readFileSync } from 'node:fs';
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { Document, WebIO } from '@gltf-transform/core';
import { AssetError } from '../../src/scene/assetError';
import { applyMatrixToTangents, decodeMesh, transformMesh } from '../../src/scene/mesh';
import { loadMikkTSpace } from '../../src/scene/mesh/mikktspace';
import { meshTangents } from '../../src/scene/mesh/tangents';
import type { TriangleMesh } from '../../src/scene/types';

type V3 = [number, number, number];
type V2 = [number, number];

const sub = (a: ArrayLike<number>, b: ArrayLike<number>): V3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a: ArrayLike<number>, b: ArrayLike<number>) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a: ArrayLike<number>, b: ArrayLike<number>): V3 => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const scale = (a: ArrayLike<number>, k: number): V3 => [a[0] * k, a[1] * k, a[2] * k];
const unit = (a: ArrayLike<number>): V3 => scale(a, 1 / Math.hypot(a[0], a[1], a[2]));

/**
 * A planar quad p = origin + a e1 + b e2 ((a, b) in the unit square),
 * uv = c + a A0 + b A1 (affine), two triangles wound so that their face
 * normal is e1 x e2; smooth (that normal at each vertex) or flat.
 */
function quad(e1: V3, e2: V3, a0: V2, a1: V2, smooth: boolean, c: V2 = [0.25, 0.5]): TriangleMesh {
  const ab: V2[] = [[0, 0], [1, 0], [1, 1], [0, 1]];
  const origin: V3 = [0.5, -1, 2];
  const positions = Float32Array.from(ab.flatMap(([a, b]) => [0, 1, 2].map((k) => origin[k] + a * e1[k] + b * e2[k])));
  const uvs = Float32Array.from(ab.flatMap(([a, b]) => [c[0] + a * a0[0] + b * a1[0], c[1] + a * a0[1] + b * a1[1]]));
  const n = unit(cross(e1, e2));
  return { positions, normals: smooth ? Float32Array.from([n, n, n, n].flat()) : null, indices: Uint32Array.from([0, 1, 2, 0, 2, 3]), uvs };
}

/** Rodrigues' rotation by `turn` radians about the unit `axis`. */
function rotation(axis: V3, turn: number): (v: V3) => V3 {
  const [c, s] = [Math.cos(turn), Math.sin(turn)];
  return (v) => {
    const k = cross(axis, v);
    const d = dot(axis, v) * (1 - c);
    return [0, 1, 2].map((i) => v[i] * c + k[i] * s + axis[i] * d) as V3;
  };
}

/** dp/du and dp/dv of triangle t (from its positions and uvs); null where its uv area is zero. */
function derivatives(mesh: TriangleMesh, t: number): { dpdu: V3; dpdv: V3 } | null {
  const [i0, i1, i2] = [0, 1, 2].map((k) => mesh.indices[t * 3 + k]);
  const p = (i: number) => mesh.positions.subarray(i * 3, i * 3 + 3);
  const uv = (i: number) => mesh.uvs!.subarray(i * 2, i * 2 + 2);
  const d1 = sub(p(i1), p(i0));
  const d2 = sub(p(i2), p(i0));
  const [du1, dv1] = [uv(i1)[0] - uv(i0)[0], uv(i1)[1] - uv(i0)[1]];
  const [du2, dv2] = [uv(i2)[0] - uv(i0)[0], uv(i2)[1] - uv(i0)[1]];
  const det = du1 * dv2 - dv1 * du2;
  if (Math.abs(det) < 1e-9) return null;
  return {
    dpdu: scale(sub(scale(d1, dv2), scale(d2, dv1)), 1 / det),
    dpdv: scale(sub(scale(d2, du1), scale(d1, du2)), 1 / det),
  };
}

/** The shading normal at corner c: the vertex normal, or the face normal of a flat mesh. */
function shadingNormal(mesh: TriangleMesh, c: number): V3 {
  const v = mesh.indices[c];
  if (mesh.normals) return [...mesh.normals.subarray(v * 3, v * 3 + 3)] as V3;
  const t = Math.floor(c / 3) * 3;
  const p = (k: number) => mesh.positions.subarray(mesh.indices[t + k] * 3, mesh.indices[t + k] * 3 + 3);
  return unit(cross(sub(p(1), p(0)), sub(p(2), p(0))));
}

const corner = (tangents: Float32Array, c: number) => ({ t: tangents.subarray(c * 4, c * 4 + 3), w: tangents[c * 4 + 3] });

/** Every corner: tangent = normalized dp/du, and cross(n, t) * w along -dp/dv (up the image). */
function expectGltfFrame(mesh: TriangleMesh, tangents: Float32Array, tolerance = 1e-5): void {
  expect(tangents.length).toBe(mesh.indices.length * 4);
  for (let c = 0; c < mesh.indices.length; c++) {
    const { dpdu, dpdv } = derivatives(mesh, Math.floor(c / 3))!;
    const { t, w } = corner(tangents, c);
    expect(dot(t, unit(dpdu))).toBeGreaterThan(1 - tolerance);
    expect(Math.abs(w)).toBe(1);
    const bitangent = scale(cross(shadingNormal(mesh, c), t), w);
    expect(dot(bitangent, unit(scale(dpdv, -1)))).toBeGreaterThan(1e-3);
  }
}

describe('MikkTSpace tangents (meshTangents)', () => {
  // The quad in z = 0 seen from +z, image upright: u along +x, v down the image along -y.
  const X: V3 = [1, 0, 0];
  const minusY: V3 = [0, -1, 0];

  it('a flat quad with affine uvs, unmirrored: tangent = dp/du, bitangent = +y, up the image (w = 1)', async () => {
    for (const smooth of [false, true]) {
      const mesh = quad(X, minusY, [1, 0], [0, 1], smooth); // face normal e1 x e2 = -z
      const tangents = (await meshTangents(mesh))!;
      expectGltfFrame(mesh, tangents);
      for (let c = 0; c < 6; c++) {
        expect([...corner(tangents, c).t]).toEqual([1, 0, 0]);
        // n = -z, so cross(n, x) = -y: w = -1 makes it +y, toward decreasing v.
        expect(corner(tangents, c).w).toBe(-1);
      }
    }
    // Wound the other way (normal +z): the same quad, now w = +1.
    const mesh = quad(minusY, X, [0, 1], [1, 0], false);
    const tangents = (await meshTangents(mesh))!;
    expectGltfFrame(mesh, tangents);
    for (let c = 0; c < 6; c++) expect([...tangents.subarray(c * 4, c * 4 + 4)]).toEqual([1, 0, 0, 1]);
  });

  it('a mirrored chart (u flipped): tangent = dp/du = -x, the bitangent still up the image (+y), where cross(n, dp/du) points down', async () => {
    const mesh = quad(minusY, X, [0, 1], [-1, 0], true); // normal +z, u along -x, v along -y
    const tangents = (await meshTangents(mesh))!;
    expectGltfFrame(mesh, tangents);
    for (let c = 0; c < 6; c++) {
      const { t, w } = corner(tangents, c);
      expect([...t]).toEqual([-1, 0, 0]);
      expect(w).toBe(-1);
      // Mitsuba's normalmap frame, y = cross(n, dp/du), is -y here: down the image.
      expect(cross([0, 0, 1], t)[1]).toBe(-1);
    }
  });

  it('any plane, any non-degenerate affine chart (mirrored or not), flat or smooth: dp/du and the bitangent up the image', async () => {
    const length = fc.double({ min: 0.2, max: 3, noNaN: true });
    const angle = fc.double({ min: 0.3, max: Math.PI - 0.3, noNaN: true }); // between the edges: no slivers
    const turn = fc.double({ min: -Math.PI, max: Math.PI, noNaN: true });
    const axis = fc.tuple(fc.double({ min: -1, max: 1, noNaN: true }), fc.double({ min: -1, max: 1, noNaN: true }), fc.double({ min: 0.1, max: 1, noNaN: true }));
    const plane = fc.record({ axis, turn, l1: length, l2: length, skew: angle });
    const chart = fc.record({ turn, m1: length, m2: length, skew: angle, mirrored: fc.boolean() });
    await fc.assert(
      fc.asyncProperty(plane, chart, fc.boolean(), async (p, c, smooth) => {
        const rotate = rotation(unit(p.axis), p.turn);
        const e1 = rotate([p.l1, 0, 0]);
        const e2 = rotate([p.l2 * Math.cos(p.skew), p.l2 * Math.sin(p.skew), 0]);
        const beta = c.turn + (c.mirrored ? -c.skew : c.skew);
        const mesh = quad(e1, e2, [c.m1 * Math.cos(c.turn), c.m1 * Math.sin(c.turn)], [c.m2 * Math.cos(beta), c.m2 * Math.sin(beta)], smooth);
        expectGltfFrame(mesh, (await meshTangents(mesh))!, 1e-4);
      }),
      { numRuns: 200, seed: 20261201 },
    );
  });

  it('texCoord 1 runs on the second set of coordinates', async () => {
    const mesh = quad(minusY, X, [0, 1], [1, 0], true); // normal +z; set 0: u along +x
    const second = quad(minusY, X, [-1, 0], [0, 1], true); // set 1: u along +y (e1 = -y), v along +x (up the image: -x)
    const tangents = (await meshTangents({ ...mesh, uvs1: second.uvs }, 1))!;
    expectGltfFrame(second, tangents);
    expect([...tangents.subarray(0, 4)]).toEqual([0, 1, 0, 1]); // cross(+z, +y) = -x, up the image
    expect(await meshTangents(mesh, 1)).toBeNull();
  });

  it('a mesh without texture coordinates has no frame (null), with or without a given TANGENT', async () => {
    const mesh = quad(X, minusY, [1, 0], [0, 1], true);
    expect(await meshTangents({ ...mesh, uvs: null })).toBeNull();
    expect(await meshTangents({ ...mesh, uvs: undefined, tangents: new Float32Array(16).fill(1) })).toBeNull();
  });

  it('a curved smooth mesh (a latitude-longitude sphere): unit tangents orthogonal to the vertex normal within 1e-4, w = +-1, bitangents up the image', async () => {
    const mesh = uvSphere(24, 48);
    const tangents = (await meshTangents(mesh))!;
    expect(tangents.length).toBe(mesh.indices.length * 4);
    for (let c = 0; c < mesh.indices.length; c++) {
      const { t, w } = corner(tangents, c);
      const n = shadingNormal(mesh, c);
      expect(Math.abs(Math.hypot(t[0], t[1], t[2]) - 1)).toBeLessThan(1e-4);
      expect(Math.abs(dot(t, n))).toBeLessThan(1e-4);
      expect(Math.abs(w)).toBe(1);
      // v = 0 at the north pole (+y), the top row: up the image is up the sphere; u runs east.
      const { dpdu, dpdv } = derivatives(mesh, Math.floor(c / 3))!;
      expect(dot(scale(cross(n, t), w), unit(scale(dpdv, -1)))).toBeGreaterThan(0.5);
      expect(dot(t, unit(dpdu))).toBeGreaterThan(0.5);
    }
  });

  it("the WebAssembly's own error (no triangles) comes back as an Error with its message, and it keeps working after; its raw w is the opposite of glTF's here", async () => {
    const generate = await loadMikkTSpace();
    expect(() => generate(new Float32Array(0), new Float32Array(0), new Float32Array(0))).toThrow(/Failed to generate tangents/);
    // Raw MikkTSpace: dp/du = +x, dp/dv = -y, n = +z; its cross(n, t) * w is dp/dv (w = -1): meshTangents negates w.
    expect([...generate(Float32Array.from([0, 0, 0, 1, 0, 0, 0, 1, 0]), Float32Array.from([0, 0, 1, 0, 0, 1, 0, 0, 1]), Float32Array.from([0, 1, 1, 1, 0, 0]))]).toEqual([1, 0, 0, -1, 1, 0, 0, -1, 1, 0, 0, -1]);
  });

  it('an empty mesh has an empty frame array', async () => {
    expect(await meshTangents({ positions: new Float32Array(0), normals: null, indices: new Uint32Array(0), uvs: new Float32Array(0) })).toEqual(new Float32Array(0));
  });

  it('degenerate triangles (zero area, repeated or collinear uvs, a zero normal) give unit tangents orthogonal to the normal and w = +-1, never NaN', async () => {
    const positions = Float32Array.from([0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 2, 0, 0, 2, 1, 0, 5, 0, 0, 6, 0, 0, 7, 0, 0]);
    const normals = Float32Array.from([0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 1, 0.6, 0, 0.8, 0, 0, 0, 0, 0, 0]);
    const uvs = Float32Array.from([0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.7, 0.5, 0.9, 0.5, 0.8, 0.2, 0.1, 0.1, 0.1, 0.1, 0.3, 0.3]);
    // Repeated uvs (0, 1, 2), a zero normal at 3 and collinear uvs (1, 3, 4 share v), zero area (0, 1, 4 collinear;
    // 0, 0, 1 repeated), beside one sound triangle (1, 3, 5) whose frame MikkTSpace spreads to its neighbours;
    // apart, a zero-area triangle with repeated uvs, a tilted normal (MikkTSpace's default (1, 0, 0) is not
    // orthogonal to it) and zero normals (MikkTSpace gives (0, 0, 0) there).
    const indices = Uint32Array.from([0, 1, 2, 1, 3, 2, 1, 4, 3, 0, 1, 4, 0, 0, 1, 1, 3, 5, 6, 7, 8]);
    for (const smooth of [true, false]) {
      const mesh: TriangleMesh = { positions, normals: smooth ? normals : null, indices, uvs };
      const tangents = (await meshTangents(mesh))!;
      expect(tangents.every(Number.isFinite)).toBe(true);
      for (let c = 0; c < indices.length; c++) {
        const { t, w } = corner(tangents, c);
        expect(Math.abs(Math.hypot(t[0], t[1], t[2]) - 1)).toBeLessThan(1e-4);
        const n = shadingNormal(mesh, c);
        if (n.every(Number.isFinite) && Math.hypot(...n) > 0) expect(Math.abs(dot(t, n))).toBeLessThan(1e-4);
        expect(Math.abs(w)).toBe(1);
      }
    }
  });
});

/** A latitude-longitude sphere, smooth, v = 0 at the north pole (+y), u east around it (seen from outside, wound outward). */
function uvSphere(rows: number, cols: number): TriangleMesh {
  const positions: number[] = [];
  const uvs: number[] = [];
  for (let i = 0; i <= rows; i++) {
    for (let j = 0; j <= cols; j++) {
      const theta = Math.PI * (0.02 + (0.96 * i) / rows); // no zero-area triangles at the poles
      const phi = (2 * Math.PI * j) / cols;
      positions.push(Math.sin(theta) * Math.cos(phi), Math.cos(theta), -Math.sin(theta) * Math.sin(phi));
      uvs.push(j / cols, i / rows);
    }
  }
  const indices: number[] = [];
  for (let i = 0; i < rows; i++) {
    for (let j = 0; j < cols; j++) {
      const a = i * (cols + 1) + j;
      const b = a + cols + 1;
      indices.push(a, b, a + 1, a + 1, b, b + 1);
    }
  }
  return { positions: Float32Array.from(positions), normals: Float32Array.from(positions), indices: Uint32Array.from(indices), uvs: Float32Array.from(uvs) };
}

/** A one-quad glTF (z = 0, normal +z, u along +x, v along -y) under a node with `node`'s TRS; `tangent` per vertex when given. */
async function quadGlb(options: { tangent?: number[] | null; normals?: boolean; translation?: V3; rotation?: [number, number, number, number]; scale?: V3; second?: boolean }): Promise<Uint8Array> {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const accessor = (type: 'VEC2' | 'VEC3' | 'VEC4' | 'SCALAR', array: Float32Array<ArrayBuffer> | Uint16Array<ArrayBuffer>) => doc.createAccessor().setType(type).setArray(array).setBuffer(buffer);
  const mesh = doc.createMesh('quad');
  const primitive = (x0: number, tangent: number[] | null | undefined) => {
    const prim = doc.createPrimitive()
      .setAttribute('POSITION', accessor('VEC3', Float32Array.from([x0, 1, 0, x0, 0, 0, x0 + 1, 0, 0, x0 + 1, 1, 0])))
      .setAttribute('TEXCOORD_0', accessor('VEC2', Float32Array.from([0, 0, 0, 1, 1, 1, 1, 0])))
      .setIndices(accessor('SCALAR', Uint16Array.from([0, 1, 2, 0, 2, 3])));
    if (options.normals !== false) prim.setAttribute('NORMAL', accessor('VEC3', Float32Array.from([0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1])));
    if (tangent) prim.setAttribute('TANGENT', accessor('VEC4', Float32Array.from([tangent, tangent, tangent, tangent].flat())));
    mesh.addPrimitive(prim);
  };
  primitive(0, options.tangent);
  if (options.second) primitive(2, null);
  const node = doc.createNode().setMesh(mesh);
  if (options.translation) node.setTranslation(options.translation);
  if (options.rotation) node.setRotation(options.rotation);
  if (options.scale) node.setScale(options.scale);
  const scene = doc.createScene('scene').addChild(doc.createNode().addChild(node));
  doc.getRoot().setDefaultScene(scene);
  return new WebIO().writeBinary(doc);
}

describe('glTF TANGENT', () => {
  it('is read as given (normalized, per vertex) and returned per corner as given, not recomputed', async () => {
    // Not MikkTSpace's (1, 0, 0, 1): a given frame is the file's own.
    const given = [Math.cos(0.5) * 2, Math.sin(0.5) * 2, 0, -1];
    const mesh = await decodeMesh(await quadGlb({ tangent: given }), 'q.glb');
    const expected = [Math.cos(0.5), Math.sin(0.5), 0, -1];
    for (let v = 0; v < 4; v++) [...mesh.tangents!.subarray(v * 4, v * 4 + 4)].forEach((x, k) => expect(x).toBeCloseTo(expected[k], 6));
    const tangents = (await meshTangents(mesh))!;
    for (let c = 0; c < 6; c++) expect([...tangents.subarray(c * 4, c * 4 + 4)]).toEqual([...mesh.tangents!.subarray(mesh.indices[c] * 4, mesh.indices[c] * 4 + 4)]);
  });

  it('a file without TANGENT, or a flat one, has none on load (nothing computed)', async () => {
    expect((await decodeMesh(await quadGlb({}), 'q.glb')).tangents).toBeNull();
    expect((await decodeMesh(await quadGlb({ tangent: [1, 0, 0, 1], normals: false }), 'q.glb')).tangents).toBeNull();
  });

  it('where one primitive gives TANGENT and another does not, the other gets MikkTSpace frames', async () => {
    const mesh = await decodeMesh(await quadGlb({ tangent: [0, 1, 0, -1], second: true }), 'q.glb');
    expect([...mesh.tangents!.subarray(16)]).toEqual(new Array(16).fill(0));
    const tangents = (await meshTangents(mesh))!;
    for (let c = 0; c < 6; c++) expect([...tangents.subarray(c * 4, c * 4 + 4)]).toEqual([0, 1, 0, -1]);
    for (let c = 6; c < 12; c++) expect([...tangents.subarray(c * 4, c * 4 + 4)]).toEqual([1, 0, 0, 1]);
  });

  it('under a mirroring node, xyz goes through the matrix and w turns over: the bitangent still points up the image', async () => {
    const unmirrored = await decodeMesh(await quadGlb({ tangent: [1, 0, 0, 1] }), 'q.glb');
    expectGltfFrame(unmirrored, (await meshTangents(unmirrored))!);
    const sin = Math.sin(0.6);
    const rotation: [number, number, number, number] = [sin * 0.48, sin * 0.6, sin * 0.64, Math.cos(0.6)];
    for (const transform of [{ scale: [-1, 1, 1] as V3 }, { translation: [1, 2, 3] as V3, rotation, scale: [-2, 0.5, 3] as V3 }]) {
      const mesh = await decodeMesh(await quadGlb({ tangent: [1, 0, 0, 1], ...transform }), 'q.glb');
      for (let v = 0; v < 4; v++) expect(mesh.tangents![v * 4 + 3]).toBe(-1);
      const given = (await meshTangents(mesh))!;
      expectGltfFrame(mesh, given);
      // MikkTSpace on the transformed triangles agrees with the transformed TANGENT.
      const computed = (await meshTangents({ ...mesh, tangents: null }))!;
      for (let i = 0; i < given.length; i++) expect(computed[i]).toBeCloseTo(given[i], 5);
    }
    const mirrorX = [-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
    expect([...applyMatrixToTangents(mirrorX, [1, 0, 0, 1, 0, 1, 0, -1, 0, 0, 0, 0])]).toEqual([-1, 0, 0, -1, 0, 1, 0, 1, 0, 0, 0, 0]);
  });

  it('transformMesh (a scene transform) carries the tangents with it', async () => {
    const mesh = await decodeMesh(await quadGlb({ tangent: [1, 0, 0, 1] }), 'q.glb');
    const world = transformMesh(mesh, { position: [1, 2, 3], rotation: [0, 0, 90], scale: [2, 1, 1] });
    for (let v = 0; v < 4; v++) [...world.tangents!.subarray(v * 4, v * 4 + 4)].forEach((x, k) => expect(x).toBeCloseTo([0, 1, 0, 1][k], 6));
    expectGltfFrame(world, (await meshTangents(world))!);
  });

  it('a non-finite TANGENT is an error naming the vertex; a zero one is taken as none given', async () => {
    await expect(decodeMesh(await quadGlb({ tangent: [1, NaN, 0, 1] }), 'q.glb')).rejects.toThrow(AssetError);
    await expect(decodeMesh(await quadGlb({ tangent: [1, NaN, 0, 1] }), 'q.glb')).rejects.toThrow(/vertex 0 has a non-finite tangent/);
    const mesh = await decodeMesh(await quadGlb({ tangent: [0, 0, 0, 1] }), 'q.glb');
    expect([...mesh.tangents!]).toEqual(new Array(16).fill(0));
    expect([...(await meshTangents(mesh))!.subarray(0, 4)]).toEqual([1, 0, 0, 1]);
  });
});

describe('the test scenes\' glTF files (no TANGENT: MikkTSpace)', () => {
  const load = (name: string) => decodeMesh(new Uint8Array(readFileSync(new URL(`../fixtures/meshes/${name}`, import.meta.url))), name);

  /** Per corner: Mitsuba's x (dp/du made orthogonal to n), and whether our y agrees with -dp/dv and with Mitsuba's cross(n, x). */
  function compareWithMitsuba(mesh: TriangleMesh, tangents: Float32Array, corner: (c: number, x: V3, n: V3, up: boolean, mitsubaY: boolean, area: number) => void): void {
    for (let t = 0; t < mesh.indices.length / 3; t++) {
      const d = derivatives(mesh, t);
      if (!d) continue;
      const p = (k: number) => mesh.positions.subarray(mesh.indices[t * 3 + k] * 3, mesh.indices[t * 3 + k] * 3 + 3);
      const area = Math.hypot(...cross(sub(p(1), p(0)), sub(p(2), p(0)))) / 2;
      for (let c = t * 3; c < t * 3 + 3; c++) {
        const n = shadingNormal(mesh, c);
        const x = unit(sub(d.dpdu, scale(n, dot(n, d.dpdu))));
        const y = scale(cross(n, tangents.subarray(c * 4, c * 4 + 3)), tangents[c * 4 + 3]);
        corner(c, x, n, dot(y, scale(d.dpdv, -1)) > 0, dot(y, cross(n, x)) > 0, area / 3);
      }
    }
  }

  it('panels.glb: on its flat panels (the normal-mapped one among them) the frame is Mitsuba\'s: x = dp/du within 1e-5, y = cross(n, x)', async () => {
    const mesh = await load('panels.glb');
    const tangents = (await meshTangents(mesh))!;
    let flatCorners = 0;
    compareWithMitsuba(mesh, tangents, (c, x, n, up, mitsubaY) => {
      const t = Math.floor(c / 3) * 3;
      const face = shadingNormal({ ...mesh, normals: null }, t);
      const flat = [0, 1, 2].every((k) => dot(shadingNormal(mesh, t + k), face) > 1 - 1e-6);
      if (!flat) return;
      flatCorners++;
      expect(dot(tangents.subarray(c * 4, c * 4 + 3), x)).toBeGreaterThan(1 - 1e-5);
      expect(up && mitsubaY).toBe(true);
    });
    expect(flatCorners).toBe(4 * 6); // four one-quad panels (the fifth primitive is curved)
  });

  it('bench.glb: the bitangent points up the image over 99.9% of the area; it is opposite to Mitsuba\'s in the mirrored charts, 5% of the area', async () => {
    const mesh = await load('bench.glb');
    const tangents = (await meshTangents(mesh))!;
    let [total, up, mirrored] = [0, 0, 0];
    compareWithMitsuba(mesh, tangents, (_c, _x, _n, isUp, mitsubaY, area) => {
      total += area;
      if (isUp) up += area;
      if (!mitsubaY) mirrored += area;
    });
    expect(up / total).toBeGreaterThan(0.999);
    expect(mirrored / total).toBeGreaterThan(0.04);
    expect(mirrored / total).toBeLessThan(0.065);
  });
});
