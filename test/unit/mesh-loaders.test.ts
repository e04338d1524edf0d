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
    await expect(decodeMesh(text(JSON.stringify(json)), 'a.gltf', { resolveResource })).rejects.toThrow(/its buffer "missing.bin" is missing \(no such file/);
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
    await expect(readMeshFile(join(dir, 'gone.gltf'))).rejects.toThrow(/its buffer "gone.bin" is missing/);
    await expect(readMeshFile(join(dir, 'missing.obj'))).rejects.toThrow(/cannot read .*missing.obj: ENOENT/);
  });
});

// ---------------------------------------------------------------- texture coordinates

/**
 * A textured strip of two quads sharing an edge, with a seam on it (the
 * shared positions p1 and p2 have other coordinates in each quad): each
 * quad's corners as [position, uv] (uv as the renderer means it: (0, 0) the
 * image's top-left). Coordinates are multiples of 1/5, which normalized
 * unsigned bytes and shorts hold exactly.
 */
const STRIP_POSITIONS = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [1, 0, -1], [1, 1, -1]];
const STRIP_QUADS: { p: number[]; uv: number[][]; uv1: number[][] }[] = [
  { p: [0, 1, 2, 3], uv: [[0, 1], [0.4, 1], [0.4, 0], [0, 0]], uv1: [[2, 0], [1.2, 0], [1.2, 2], [2, 2]] },
  { p: [1, 4, 5, 2], uv: [[0.6, 1], [1, 0.8], [1, 0.2], [0.6, 0]], uv1: [[0.8, 0], [0, 0.4], [0, 1.6], [0.8, 2]] },
];
/** The strip de-indexed (one vertex per quad corner, 8 in all), `scale` times the coordinates. */
function stripVertices(scale = 1, set: 'uv' | 'uv1' = 'uv'): number[][] {
  return STRIP_QUADS.flatMap((q) => q.p.map((p, k) => [...STRIP_POSITIONS[p], ...q[set][k].map((c) => c * scale)]));
}
const STRIP_FACES = [[0, 1, 2, 3], [4, 5, 6, 7]];

/** Each triangle's corners as [x, y, z, u, v] of `set`, rotated to start at the smallest position, sorted (positions decide the order). */
function uvCorners(mesh: TriangleMesh, set: 'uvs' | 'uvs1' = 'uvs'): number[][][] {
  const uvs = mesh[set];
  if (!uvs) throw new Error(`the mesh has no ${set}`);
  const out: number[][][] = [];
  for (let t = 0; t < mesh.indices.length / 3; t++) {
    const tri = [0, 1, 2].map((k) => {
      const v = mesh.indices[t * 3 + k];
      return [...mesh.positions.subarray(v * 3, v * 3 + 3), ...uvs.subarray(v * 2, v * 2 + 2)];
    });
    const first = [0, 1, 2].reduce((best, k) => (compare(tri[k].slice(0, 3), tri[best].slice(0, 3)) < 0 ? k : best), 0);
    out.push([0, 1, 2].map((k) => tri[(first + k) % 3]));
  }
  return out.sort((a, b) => compare(a.flatMap((c) => c.slice(0, 3)), b.flatMap((c) => c.slice(0, 3))));
}

/** The strip's triangles (fan-triangulated quads) as uvCorners gives them. */
function expectedStrip(scale = 1, set: 'uv' | 'uv1' = 'uv'): number[][][] {
  const vertices = stripVertices(scale, set);
  const mesh: TriangleMesh = {
    positions: Float32Array.from(vertices.flatMap((v) => v.slice(0, 3))),
    normals: null,
    indices: Uint32Array.from(STRIP_FACES.flatMap((f) => [f[0], f[1], f[2], f[0], f[2], f[3]])),
    uvs: Float32Array.from(vertices.flatMap((v) => v.slice(3))),
  };
  return uvCorners(mesh);
}

/** Same triangles, positions exactly, coordinates to float precision. */
function expectStrip(mesh: TriangleMesh, expected: number[][][], set: 'uvs' | 'uvs1' = 'uvs'): void {
  const actual = uvCorners(mesh, set);
  expect(actual.length).toBe(expected.length);
  actual.forEach((tri, t) => tri.forEach((corner, k) => {
    expect(corner.slice(0, 3)).toEqual(expected[t][k].slice(0, 3));
    corner.slice(3).forEach((c, j) => expect(Math.abs(c - expected[t][k][3 + j]), `triangle ${t} corner ${k}`).toBeLessThan(1e-6));
  }));
}

/** The strip as OBJ: shared positions, one `vt` per quad corner (stored with v turned over, as OBJ counts it), optional normals. */
function stripObj(withNormals: boolean): string {
  const lines = STRIP_POSITIONS.map((p) => `v ${p.join(' ')}`);
  for (const q of STRIP_QUADS) for (const [u, v] of q.uv) lines.push(`vt ${u} ${(1 - v).toFixed(1)}`);
  if (withNormals) lines.push('vn 0 0 1', 'vn 1 0 0');
  STRIP_QUADS.forEach((q, f) => lines.push(`f ${q.p.map((p, k) => `${p + 1}/${f * 4 + k + 1}${withNormals ? `/${f + 1}` : ''}`).join(' ')}`));
  return `${lines.join('\n')}\n`;
}

type PlyFormat = 'ascii' | 'binary_little_endian' | 'binary_big_endian';
const PLY_SETTERS: Record<string, [number, (view: DataView, at: number, value: number, little: boolean) => void]> = {
  uchar: [1, (d, o, x) => d.setUint8(o, x)],
  ushort: [2, (d, o, x, l) => d.setUint16(o, x, l)],
  int: [4, (d, o, x, l) => d.setInt32(o, x, l)],
  float: [4, (d, o, x, l) => d.setFloat32(o, x, l)],
  double: [8, (d, o, x, l) => d.setFloat64(o, x, l)],
};

/** The strip as PLY: x y z float, an unrelated uchar, then the coordinates under `names` in `type`; quads as uchar/int lists. */
function stripPly(format: PlyFormat, names: readonly [string, string], type: string, scale = 1, vertices = stripVertices(scale)): Uint8Array {
  const header = [
    'ply', `format ${format} 1.0`, `element vertex ${vertices.length}`,
    'property float x', 'property float y', 'property float z', 'property uchar flag',
    `property ${type} ${names[0]}`, `property ${type} ${names[1]}`,
    `element face ${STRIP_FACES.length}`, 'property list uchar int vertex_indices', 'end_header', '',
  ].join('\n');
  const rows: [string, number][][] = [
    ...vertices.map((v) => [['float', v[0]], ['float', v[1]], ['float', v[2]], ['uchar', 7], [type, v[3]], [type, v[4]]] as [string, number][]),
    ...STRIP_FACES.map((f) => [['uchar', f.length], ...f.map((i) => ['int', i])] as [string, number][]),
  ];
  if (format === 'ascii') return text(header + rows.map((r) => r.map(([, x]) => x).join(' ')).join('\n') + '\n');
  const size = rows.flat().reduce((sum, [t]) => sum + PLY_SETTERS[t][0], 0);
  const head = text(header);
  const out = new Uint8Array(head.length + size);
  out.set(head);
  const view = new DataView(out.buffer);
  let offset = head.length;
  for (const [t, x] of rows.flat()) {
    PLY_SETTERS[t][1](view, offset, x, format === 'binary_little_endian');
    offset += PLY_SETTERS[t][0];
  }
  return out;
}

type TexcoordKind = 'float' | 'ushort' | 'ubyte';

/** The strip as glTF, one primitive per quad; which attributes each primitive gets is up to the caller. */
async function stripGltf(options: { texcoord0?: TexcoordKind | null; texcoord1?: boolean; bare?: 'TEXCOORD_0' | 'TEXCOORD_1'; nan?: boolean }) {
  const { Document } = await import('@gltf-transform/core');
  const doc = new Document();
  const buffer = doc.createBuffer();
  const mesh = doc.createMesh('strip');
  const vertices = stripVertices();
  const vertices1 = stripVertices(1, 'uv1');
  STRIP_QUADS.forEach((_q, f) => {
    const rows = vertices.slice(f * 4, f * 4 + 4);
    const accessor = (type: 'VEC2' | 'VEC3' | 'SCALAR', array: Float32Array<ArrayBuffer> | Uint16Array<ArrayBuffer> | Uint8Array<ArrayBuffer>) => doc.createAccessor().setType(type).setArray(array).setBuffer(buffer);
    const prim = doc.createPrimitive()
      .setAttribute('POSITION', accessor('VEC3', Float32Array.from(rows.flatMap((v) => v.slice(0, 3)))))
      .setIndices(accessor('SCALAR', Uint16Array.from([0, 1, 2, 0, 2, 3])));
    const uv = rows.flatMap((v) => v.slice(3));
    if (options.nan && f === 1) uv[3] = NaN;
    const kind = options.texcoord0 === undefined ? 'float' : options.texcoord0;
    if (kind && !(options.bare === 'TEXCOORD_0' && f === 1)) {
      const array = kind === 'float' ? Float32Array.from(uv) : kind === 'ushort' ? Uint16Array.from(uv, (x) => Math.round(x * 65535)) : Uint8Array.from(uv, (x) => Math.round(x * 255));
      prim.setAttribute('TEXCOORD_0', accessor('VEC2', array).setNormalized(kind !== 'float'));
    }
    if (options.texcoord1 && !(options.bare === 'TEXCOORD_1' && f === 1)) {
      prim.setAttribute('TEXCOORD_1', accessor('VEC2', Float32Array.from(vertices1.slice(f * 4, f * 4 + 4).flatMap((v) => v.slice(3)))));
    }
    mesh.addPrimitive(prim);
  });
  const scene = doc.createScene('scene').addChild(doc.createNode().setMesh(mesh));
  doc.getRoot().setDefaultScene(scene);
  return doc;
}

/** A glTF Document as .glb bytes and as a .gltf with its buffer embedded (data: URI). */
async function gltfFiles(doc: Awaited<ReturnType<typeof stripGltf>>): Promise<[string, Uint8Array][]> {
  const { WebIO } = await import('@gltf-transform/core');
  const io = new WebIO();
  const { json, resources } = await io.writeJSON(doc);
  for (const buffer of json.buffers ?? []) buffer.uri = `data:application/octet-stream;base64,${Buffer.from(resources[buffer.uri!]).toString('base64')}`;
  return [['strip.glb', await io.writeBinary(doc)], ['strip.gltf', text(JSON.stringify(json))]];
}

describe('texture coordinates: the same textured strip in every format', () => {
  const expected = expectedStrip();

  for (const withNormals of [false, true]) {
    it(`OBJ vt (v turned over), one vertex per distinct (v, vt${withNormals ? ', vn' : ''})`, async () => {
      const mesh = await decodeMesh(text(stripObj(withNormals)), 'strip.obj');
      expectStrip(mesh, expected);
      expect(mesh.positions.length / 3).toBe(8); // the seam splits p1 and p2
      expect(mesh.normals !== null).toBe(withNormals);
      expect(mesh.uvs1).toBeNull();
    });
  }

  it('OBJ with negative (relative) vt indices and a vt without v (v = 0, turned over to 1)', async () => {
    const mesh = await decodeMesh(text('v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5\nvt 1 0\nvt 0 1\nf 1/-3 2/-2 3/-1\n'), 'a.obj');
    expect(Array.from(mesh.uvs!)).toEqual([0.5, 1, 1, 1, 0, 0]);
  });

  for (const format of ['ascii', 'binary_little_endian', 'binary_big_endian'] as const) {
    for (const [names, type] of [[['u', 'v'], 'float'], [['s', 't'], 'double'], [['texture_u', 'texture_v'], 'float']] as const) {
      it(`PLY ${format}, ${names.join(' ')} (${type})`, async () => {
        const mesh = await decodeMesh(stripPly(format, names, type), 'strip.ply');
        expectStrip(mesh, expected);
        expect(mesh.uvs1).toBeNull();
      });
    }
    it(`PLY ${format}, integer coordinates (ushort u v, uchar texture_u texture_v) as stored`, async () => {
      expectStrip(await decodeMesh(stripPly(format, ['u', 'v'], 'ushort', 5), 'strip.ply'), expectedStrip(5));
      expectStrip(await decodeMesh(stripPly(format, ['texture_u', 'texture_v'], 'uchar', 5), 'strip.ply'), expectedStrip(5));
    });
  }

  it('PLY with only one of a pair (u without v) has no coordinates', async () => {
    const ply = new TextDecoder().decode(stripPly('ascii', ['u', 'w'], 'float'));
    expect((await decodeMesh(text(ply), 'a.ply')).uvs).toBeNull();
  });

  for (const kind of ['float', 'ushort', 'ubyte'] as const) {
    it(`glTF TEXCOORD_0 (${kind}${kind === 'float' ? '' : ', normalized'}) and TEXCOORD_1, .glb and .gltf, over two primitives`, async () => {
      for (const [name, bytes] of await gltfFiles(await stripGltf({ texcoord0: kind, texcoord1: true }))) {
        const mesh = await decodeMesh(bytes, name);
        expectStrip(mesh, expected);
        expectStrip(mesh, expectedStrip(1, 'uv1'), 'uvs1');
      }
    });
  }

  it('glTF: a set that one primitive lacks is zeros on its vertices (its material must not be textured); without TEXCOORD_1 uvs1 is null', async () => {
    const halves = (uvs: Float32Array) => [Array.from(uvs.subarray(0, uvs.length / 2)), Array.from(uvs.subarray(uvs.length / 2))];
    for (const [name, bytes] of await gltfFiles(await stripGltf({ texcoord1: true, bare: 'TEXCOORD_1' }))) {
      const mesh = await decodeMesh(bytes, name);
      expectStrip(mesh, expected);
      const [first, second] = halves(mesh.uvs1!);
      expect(first.some((x) => x !== 0)).toBe(true);
      expect(second.every((x) => x === 0)).toBe(true);
    }
    for (const [name, bytes] of await gltfFiles(await stripGltf({ texcoord1: true, bare: 'TEXCOORD_0' }))) {
      const mesh = await decodeMesh(bytes, name);
      expect(halves(mesh.uvs!)[1].every((x) => x === 0)).toBe(true);
      expectStrip(mesh, expectedStrip(1, 'uv1'), 'uvs1');
    }
    for (const [name, bytes] of await gltfFiles(await stripGltf({}))) expect((await decodeMesh(bytes, name)).uvs1).toBeNull();
  });

  it('encodePly writes u v, which the PLY decoder reads back; transformMesh keeps the coordinates', async () => {
    const { transformMesh } = await import('../../src/scene/mesh');
    const mesh = await decodeMesh(text(stripObj(true)), 'strip.obj');
    const encoded = encodePly(mesh);
    expect(new TextDecoder('latin1').decode(encoded.subarray(0, 300))).toMatch(/property float nz\nproperty float u\nproperty float v\nelement face/);
    expectStrip(await decodeMesh(encoded, 'out.ply'), expected);
    const moved = transformMesh(mesh, { position: [1, 2, 3], rotation: [10, 20, 30], scale: [-1, 2, 1] }); // mirrored: winding flips
    expect(Array.from(moved.uvs!)).toEqual(Array.from(mesh.uvs!));
    expect(moved.uvs1).toBeNull();
  });

  it('files without coordinates give null (the icospheres; an OBJ where only some corners name a vt)', async () => {
    for (const tag of ['flat', 'smooth']) {
      for (const file of [`ico-${tag}.obj`, `ico-${tag}-ascii.ply`, `ico-${tag}-le.ply`, `ico-${tag}.gltf`, `ico-${tag}.glb`, `ico-${tag}-draco.glb`]) {
        const mesh = await load(file);
        expect(mesh.uvs, file).toBeNull();
        expect(mesh.uvs1, file).toBeNull();
      }
    }
    // ico-flat.obj names vt on every other triangle only.
    expect(readFileSync(new URL('ico-flat.obj', FIXTURES), 'utf8')).toMatch(/\d+\/1/);
    expect(encodePly(await load('ico-smooth.obj')).length).toBe(encodePly(icosphere(1, true)).length); // no u v properties
  });

  it('uvbox.obj (a version-3 fixture): 24 vertices, each face mapped over the whole image, v turned over', async () => {
    const mesh = await load('uvbox.obj');
    expect(mesh.indices.length / 3).toBe(12);
    expect(mesh.positions.length / 3).toBe(24);
    expect(mesh.normals).not.toBeNull();
    // The first face: v 1..4 with vt (0,0) (1,0) (1,1) (0,1), read as (0,1) (1,1) (1,0) (0,0).
    const uvOf = (x: number, y: number, z: number, nx: number) => {
      for (let v = 0; v < 24; v++) {
        const p = mesh.positions.subarray(v * 3, v * 3 + 3);
        if (p[0] === x && p[1] === y && p[2] === z && mesh.normals![v * 3] === nx) return Array.from(mesh.uvs!.subarray(v * 2, v * 2 + 2));
      }
      throw new Error('no such vertex');
    };
    expect([uvOf(0.5, -0.5, -0.5, 1), uvOf(0.5, 0.5, -0.5, 1), uvOf(0.5, 0.5, 0.5, 1), uvOf(0.5, -0.5, 0.5, 1)]).toEqual([[0, 1], [1, 1], [1, 0], [0, 0]]);
    for (let f = 0; f < 6; f++) {
      const corners = new Set<string>();
      for (let t = f * 2; t < f * 2 + 2; t++) for (let k = 0; k < 3; k++) corners.add(Array.from(mesh.uvs!.subarray(mesh.indices[t * 3 + k] * 2, mesh.indices[t * 3 + k] * 2 + 2)).join(','));
      expect([...corners].sort()).toEqual(['0,0', '0,1', '1,0', '1,1']);
    }
  });
});

describe('texture coordinates: bad ones give an AssetError saying why', () => {
  const nanPly = new TextDecoder().decode(stripPly('ascii', ['u', 'v'], 'float')).replace(/^(1 0 0 7) 0\.4 1$/m, '$1 inf 1');
  const cases: [string, string, () => Promise<Uint8Array>, RegExp][] = [
    ['OBJ NaN vt', 'a.obj', async () => text('v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt nan 0\nf 1/1 2/2 3/1\n'), /line 5: texture coordinate 1 is not finite/],
    ['OBJ infinite vt', 'a.obj', async () => text('v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 1e999\nf 1/1 2/1 3/1\n'), /line 4: texture coordinate 0 is not finite/],
    ['OBJ empty vt', 'a.obj', async () => text('vt\n'), /line 1: "vt" needs at least 1 number/],
    ['OBJ vt index out of range', 'a.obj', async () => text('v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/2\n'), /line 5: texture coordinate index 2 is out of range/],
    ['PLY infinite u', 'a.ply', async () => text(nanPly), /vertex 1 has a non-finite texture coordinate \(Infinity\)/],
    ['PLY binary NaN v', 'a.ply', async () => stripPly('binary_big_endian', ['s', 't'], 'float', 1, stripVertices().map((v, i) => (i === 5 ? [...v.slice(0, 4), NaN] : v))), /vertex 5 has a non-finite texture coordinate/],
    ['PLY u beyond float range', 'a.ply', async () => text(nanPly.replace('inf 1', '1e300 1')), /vertex 1 has a non-finite texture coordinate \(1e\+300\)/],
    ['glTF NaN TEXCOORD_0', 'strip.glb', async () => (await gltfFiles(await stripGltf({ nan: true })))[0][1], /vertex 5 has a non-finite texture coordinate/],
  ];
  for (const [name, file, bytes, message] of cases) {
    it(name, async () => {
      const error = await decodeMesh(await bytes(), file).then(() => null, (e: unknown) => e);
      expect(error).toBeInstanceOf(AssetError);
      expect((error as Error).message).toMatch(message);
    });
  }
});
