/**
 * The mesh decoders: one icosphere, flat and smooth, written as OBJ, PLY
 * (ASCII, binary LE/BE), glTF, GLB and Draco GLB by
 * scripts/make-mesh-fixtures.ts, decodes to the same triangles (same winding,
 * same normals) in every format; the shared meshes load; bad files fail with
 * an AssetError that says what is wrong.
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { decodeMesh, encodePly } from '../../src/scene/mesh';
import { AssetError } from '../../src/scene/assetError';
import type { TriangleMesh } from '../../src/scene/types';
import { icosphere } from '../support/icosphere';

const FIXTURES = new URL('../fixtures/meshes/', import.meta.url);
const load = (name: string) => decodeMesh(new Uint8Array(readFileSync(new URL(name, FIXTURES))), name);

/** Each triangle as 3 corners (position + normal), rotated to start at its smallest corner (keeps the winding). */
function corners(mesh: TriangleMesh): number[][][] {
  const out: number[][][] = [];
  for (let t = 0; t < mesh.indices.length / 3; t++) {
    const tri = [0, 1, 2].map((k) => {
      const v = mesh.indices[t * 3 + k];
      return [...mesh.positions.subarray(v * 3, v * 3 + 3), ...(mesh.normals ? mesh.normals.subarray(v * 3, v * 3 + 3) : [])];
    });
    const first = [0, 1, 2].reduce((best, k) => (compare(tri[k], tri[best]) < 0 ? k : best), 0);
    out.push([0, 1, 2].map((k) => tri[(first + k) % 3]));
  }
  return out.sort((a, b) => compare(a.flat(), b.flat()));
}

function compare(a: number[], b: number[]): number {
  for (let i = 0; i < a.length; i++) if (a[i] !== b[i]) return a[i] - b[i];
  return 0;
}

/** Same triangles up to `tolerance` per coordinate, matched by nearest centroid (Draco reorders and quantizes). */
function expectSameTriangles(actual: TriangleMesh, expected: TriangleMesh, tolerance: number): void {
  expect(actual.indices.length).toBe(expected.indices.length);
  expect(actual.normals !== null).toBe(expected.normals !== null);
  const a = corners(actual);
  const e = corners(expected);
  if (tolerance === 0) {
    expect(a).toEqual(e);
    return;
  }
  const centroid = (tri: number[][]) => [0, 1, 2].map((k) => (tri[0][k] + tri[1][k] + tri[2][k]) / 3);
  for (const tri of e) {
    const c = centroid(tri);
    const match = a.reduce((best, cand) => (dist(centroid(cand), c) < dist(centroid(best), c) ? cand : best));
    for (let k = 0; k < 3; k++) {
      for (let j = 0; j < tri[k].length; j++) expect(Math.abs(match[k][j] - tri[k][j])).toBeLessThan(tolerance);
    }
  }
}

const dist = (p: number[], q: number[]) => Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);

describe('the same icosphere in every format', () => {
  for (const smooth of [false, true]) {
    const tag = smooth ? 'smooth' : 'flat';
    const reference = icosphere(1, smooth);
    for (const [file, tolerance] of [
      [`ico-${tag}.obj`, 0], [`ico-${tag}-ascii.ply`, 0], [`ico-${tag}-le.ply`, 0], [`ico-${tag}-be.ply`, 0],
      [`ico-${tag}.gltf`, 0], [`ico-${tag}.glb`, 0], [`ico-${tag}-draco.glb`, 2e-3],
    ] as const) {
      it(`${file} (${tag})`, async () => {
        expectSameTriangles(await load(file), reference, tolerance);
      });
    }
  }

  it('encodePly round-trips through the PLY decoder (smooth and flat)', async () => {
    for (const smooth of [false, true]) {
      const mesh = icosphere(2, smooth);
      expectSameTriangles(await decodeMesh(encodePly(mesh), 'out.ply'), mesh, 0);
    }
  });

  it('glTF node transforms are applied (instances, a parent translation, a rotation)', async () => {
    const mesh = await load('ico-nodes.gltf');
    const base = icosphere(1, true);
    const n = base.positions.length / 3;
    expect(mesh.indices.length).toBe(base.indices.length * 2);
    // First instance: translate (2,0,0) * scale (1,2,1); normals by the inverse transpose.
    // Second: translate (0,3,0) * rotate 90 deg about +z: (x,y,z) -> (-y,x,z).
    const close = (a: number, b: number) => expect(Math.abs(a - b)).toBeLessThan(1e-5);
    for (let v = 0; v < n; v++) {
      const [x, y, z] = base.positions.subarray(v * 3, v * 3 + 3);
      const p0 = mesh.positions.subarray(v * 3, v * 3 + 3);
      const p1 = mesh.positions.subarray((n + v) * 3, (n + v) * 3 + 3);
      [x + 2, 2 * y, z].forEach((e, k) => close(p0[k], e));
      [-y, x + 3, z].forEach((e, k) => close(p1[k], e));
      const nScaled = [x, y / 2, z];
      const len = Math.hypot(...nScaled);
      nScaled.forEach((e, k) => close(mesh.normals![v * 3 + k], e / len));
      [-y, x, z].forEach((e, k) => close(mesh.normals![(n + v) * 3 + k], e));
    }
  });

  it('a mirroring glTF node (negative determinant) keeps every face wound outward, as glTF requires', async () => {
    const json = JSON.parse(readFileSync(new URL('ico-flat.gltf', FIXTURES), 'utf8'));
    for (const scale of [[1, 1, 1], [-1, 1, 1], [1, -2, 0.5], [-1, -1, -1]]) {
      json.nodes[0].scale = scale;
      const mesh = await decodeMesh(new TextEncoder().encode(JSON.stringify(json)), 'a.gltf');
      let outward = 0;
      for (let t = 0; t < mesh.indices.length / 3; t++) {
        const [a, b, c] = [0, 1, 2].map((k) => Array.from(mesh.positions.subarray(mesh.indices[t * 3 + k] * 3, mesh.indices[t * 3 + k] * 3 + 3)));
        const e1 = [0, 1, 2].map((k) => b[k] - a[k]);
        const e2 = [0, 1, 2].map((k) => c[k] - a[k]);
        const normal = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
        // The icosphere is centred on the origin: outward = along the centroid.
        if (normal.reduce((sum, v, k) => sum + v * (a[k] + b[k] + c[k]), 0) > 0) outward++;
      }
      expect(outward, `scale ${scale}`).toBe(mesh.indices.length / 3);
    }
  });
});

describe('the shared meshes', () => {
  it('bunny.ply: 3674 smooth triangles', async () => {
    const mesh = await load('bunny.ply');
    expect(mesh.indices.length / 3).toBe(3674);
    expect(mesh.normals).not.toBeNull();
  });
  it('gem.obj: 80 flat triangles', async () => {
    const mesh = await load('gem.obj');
    expect(mesh.indices.length / 3).toBe(80);
    expect(mesh.normals).toBeNull();
  });
});

const text = (s: string) => new TextEncoder().encode(s);
const TRI_PLY = (count: number, body: string, extra = '') => `ply\nformat ascii 1.0\nelement vertex ${count}\nproperty float x\nproperty float y\nproperty float z\n${extra}element face 1\nproperty list uchar int vertex_indices\nend_header\n${body}`;

describe('bad files give an AssetError saying why', () => {
  const validPly = readFileSync(new URL('ico-flat-le.ply', FIXTURES));
  const validGlb = new Uint8Array(readFileSync(new URL('ico-flat.glb', FIXTURES)));
  const cases: [string, string, Uint8Array, RegExp][] = [
    ['empty file', 'a.obj', new Uint8Array(0), /empty/],
    ['unknown extension', 'a.stl', text('solid'), /unsupported mesh file type/],
    ['OBJ without faces', 'a.obj', text('v 0 0 0\nv 1 0 0\n'), /no faces/],
    ['OBJ NaN vertex', 'a.obj', text('v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n'), /line 2.*non-finite/],
    ['OBJ infinite vertex', 'a.obj', text('v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n'), /non-finite/],
    ['OBJ index out of range', 'a.obj', text('v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n'), /line 4: vertex index 4 is out of range/],
    ['OBJ normal index out of range', 'a.obj', text('v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n'), /normal index 2 is out of range/],
    ['OBJ bad index', 'a.obj', text('v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n'), /"x" is not a valid vertex index/],
    ['OBJ short face', 'a.obj', text('v 0 0 0\nv 1 0 0\nf 1 2\n'), /at least 3 corners/],
    ['OBJ only degenerate triangles', 'a.obj', text('v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n'), /zero area/],
    ['binary garbage as OBJ', 'a.obj', new Uint8Array([0, 255, 3, 7, 9, 10, 200]), /no faces/],
    ['not a PLY', 'a.ply', text('hello\n'), /not a PLY file/],
    ['PLY unknown format', 'a.ply', text('ply\nformat binary_middle_endian 1.0\nend_header\n'), /unknown PLY format/],
    ['PLY header count larger than the data (ascii)', 'a.ply', text(TRI_PLY(4, '0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n')), /ends before the data/],
    ['PLY header count larger than the data (binary)', 'a.ply', new Uint8Array(validPly.subarray(0, validPly.length - 40)), /ends before the data/],
    ['PLY index out of range', 'a.ply', text(TRI_PLY(3, '0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n')), /references vertex 3, but the file has 3 vertices/],
    ['PLY negative index', 'a.ply', text(TRI_PLY(3, '0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n')), /references vertex -1/],
    ['PLY NaN vertex', 'a.ply', text(TRI_PLY(3, '0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n')), /vertex 1 has a non-finite coordinate/],
    ['PLY not a number', 'a.ply', text(TRI_PLY(3, '0 0 0\nabc 0 0\n0 1 0\n3 0 1 2\n')), /"abc" .* not a number/],
    ['PLY without faces', 'a.ply', text('ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n'), /no triangles/],
    ['PLY without x', 'a.ply', text('ply\nformat ascii 1.0\nelement vertex 1\nproperty float y\nproperty float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n0 0\n'), /lacks x, y or z/],
    ['PLY unknown property type', 'a.ply', text('ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n'), /unknown type "quad"/],
    ['PLY non-finite normal', 'a.ply', text(TRI_PLY(3, '0 0 0 0 0 1\n1 0 0 0 0 inf\n0 1 0 0 0 1\n3 0 1 2\n').replace('property float z\n', 'property float z\nproperty float nx\nproperty float ny\nproperty float nz\n')), /vertex 1 has a non-finite normal/],
    ['GLB with a bad magic', 'a.glb', text('not a glb file at all, really'), /not a GLB file/],
    ['GLB truncated', 'a.glb', validGlb.slice(0, validGlb.length - 100), /glTF/],
    ['glTF not JSON', 'a.gltf', text('{"asset": '), /not a valid glTF file/],
    ['glTF without meshes', 'a.gltf', text('{"asset":{"version":"2.0"},"scenes":[{"nodes":[]}],"scene":0}'), /no triangle primitive/],
    ['glTF external buffer without a resolver', 'a.gltf', text('{"asset":{"version":"2.0"},"buffers":[{"uri":"mesh.bin","byteLength":36}]}'), /external buffer "mesh.bin"/],
  ];
  for (const [name, file, bytes, message] of cases) {
    it(name, async () => {
      const error = await decodeMesh(bytes, file).then(() => null, (e: unknown) => e);
      expect(error).toBeInstanceOf(AssetError);
      expect((error as Error).message).toMatch(message);
    });
  }

  it('glTF index out of range', async () => {
    const json = JSON.parse(readFileSync(new URL('ico-flat.gltf', FIXTURES), 'utf8'));
    const uri: string = json.buffers[0].uri;
    const bytes = Buffer.from(uri.slice(uri.indexOf(',') + 1), 'base64');
    const indexView = json.bufferViews[json.accessors[json.meshes[0].primitives[0].indices].bufferView];
    bytes.writeUInt16LE(999, indexView.byteOffset ?? 0);
    json.buffers[0].uri = `data:application/octet-stream;base64,${bytes.toString('base64')}`;
    await expect(decodeMesh(text(JSON.stringify(json)), 'a.gltf')).rejects.toThrow(/references vertex 999/);
  });

  it('glTF external buffer through the resolver', async () => {
    const json = JSON.parse(readFileSync(new URL('ico-flat.gltf', FIXTURES), 'utf8'));
    const uri: string = json.buffers[0].uri;
    const bin = new Uint8Array(Buffer.from(uri.slice(uri.indexOf(',') + 1), 'base64'));
    json.buffers[0].uri = 'ico.bin';
    const resolveResource = async (name: string) => {
      if (name !== 'ico.bin') throw new Error(`no such file ${name}`);
      return bin;
    };
    const mesh = await decodeMesh(text(JSON.stringify(json)), 'a.gltf', { resolveResource });
    expectSameTriangles(mesh, icosphere(1, false), 0);
    json.buffers[0].uri = 'missing.bin';
    await expect(decodeMesh(text(JSON.stringify(json)), 'a.gltf', { resolveResource })).rejects.toThrow(/cannot read the glTF's buffer "missing.bin": no such file/);
  });

  it('degenerate triangles are dropped, the rest kept', async () => {
    const mesh = await decodeMesh(text('v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\nf 1 1 4\n'), 'a.obj');
    expect(Array.from(mesh.indices)).toEqual([0, 1, 3]);
  });

  it('a quad and a pentagon are fan-triangulated', async () => {
    const mesh = await decodeMesh(text('v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 0.5 0\nf 1 2 3 4\nf -5 -4 -3 -2 -1\n'), 'a.obj');
    expect(Array.from(mesh.indices)).toEqual([0, 1, 2, 0, 2, 3, 0, 1, 2, 0, 2, 3, 0, 3, 4]);
  });
});

describe('readMeshFile (the CLI side)', () => {
  it('resolves a .gltf external buffer next to the file, and reports a missing one or a missing file', async () => {
    const { mkdtempSync, writeFileSync } = await import('node:fs');
    const { tmpdir } = await import('node:os');
    const { join } = await import('node:path');
    const { readMeshFile } = await import('../../src/node/readMesh');
    const dir = mkdtempSync(join(tmpdir(), 'mesh-'));
    const json = JSON.parse(readFileSync(new URL('ico-smooth.gltf', FIXTURES), 'utf8'));
    const uri: string = json.buffers[0].uri;
    writeFileSync(join(dir, 'ico data.bin'), Buffer.from(uri.slice(uri.indexOf(',') + 1), 'base64'));
    json.buffers[0].uri = 'ico%20data.bin';
    writeFileSync(join(dir, 'ico.gltf'), JSON.stringify(json));
    expectSameTriangles(await readMeshFile(join(dir, 'ico.gltf')), icosphere(1, true), 0);
    json.buffers[0].uri = 'gone.bin';
    writeFileSync(join(dir, 'gone.gltf'), JSON.stringify(json));
    await expect(readMeshFile(join(dir, 'gone.gltf'))).rejects.toThrow(/cannot read the glTF's buffer "gone.bin"/);
    await expect(readMeshFile(join(dir, 'missing.obj'))).rejects.toThrow(/cannot read .*missing.obj: ENOENT/);
  });
});
