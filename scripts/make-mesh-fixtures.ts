/**
 * Writes the loader fixtures under test/fixtures/meshes/: one icosphere
 * (1 subdivision, 80 triangles), flat and smooth, as OBJ, PLY (ASCII,
 * binary little- and big-endian), glTF (embedded buffer), GLB and
 * Draco-compressed GLB, plus a glTF whose nodes transform and instance the
 * mesh. Also ico-padded.ply (binary little-endian, encodePly), the instancing
 * fixture's shared file: the smooth 1-subdivision icosphere (80 triangles,
 * coarse, so shading depends visibly on how an instance's vertex normals are
 * interpolated) around a hidden 6-subdivision icosphere of radius 0.5 (81920
 * triangles, vertex normals too: a PLY has normals for every vertex or none)
 * that pads the file past the instancing threshold (groups.ts,
 * INSTANCE_MIN_SAVED_TRIANGLES). Run: npx tsx scripts/make-mesh-fixtures.ts
 */
import { writeFileSync } from 'node:fs';
import { Document, WebIO, type Node } from '@gltf-transform/core';
import { KHRDracoMeshCompression } from '@gltf-transform/extensions';
import draco3d from 'draco3dgltf';
import { icosphere } from '../test/support/icosphere';
import { encodePly } from '../src/scene/mesh';
import type { TriangleMesh } from '../src/scene/types';

const OUT = new URL('../test/fixtures/meshes/', import.meta.url);
const f32 = (x: number) => Math.fround(x).toPrecision(9); // exact float32 round trip

function obj(mesh: TriangleMesh): string {
  const lines = ['# icosphere, written by scripts/make-mesh-fixtures.ts'];
  for (let v = 0; v < mesh.positions.length / 3; v++) lines.push(`v ${[0, 1, 2].map((k) => f32(mesh.positions[v * 3 + k])).join(' ')}`);
  if (mesh.normals) for (let v = 0; v < mesh.normals.length / 3; v++) lines.push(`vn ${[0, 1, 2].map((k) => f32(mesh.normals![v * 3 + k])).join(' ')}`);
  lines.push('vt 0 0', 'g sphere', 's 1');
  for (let t = 0; t < mesh.indices.length / 3; t++) {
    // Mix index forms: absolute and negative (relative), with and without texture indices.
    const corner = (i: number) => {
      const v = mesh.indices[t * 3 + i] + 1;
      if (!mesh.normals) return t % 2 ? `${v}/1` : `${v}`;
      return t % 2 ? `${v}/1/${v}` : `${v}//${v}`;
    };
    lines.push(`f ${corner(0)} ${corner(1)} ${corner(2)}`);
  }
  return lines.join('\n') + '\n';
}

function plyHeader(mesh: TriangleMesh, format: string): string {
  return [
    'ply', `format ${format} 1.0`, 'comment icosphere', `element vertex ${mesh.positions.length / 3}`,
    'property float x', 'property float y', 'property float z',
    ...(mesh.normals ? ['property float nx', 'property float ny', 'property float nz'] : []),
    'property uchar red', // an extra property the reader must step over
    `element face ${mesh.indices.length / 3}`, 'property list uchar int vertex_indices',
    'element extra 2', 'property list uchar float values', 'end_header', '',
  ].join('\n');
}

function plyAscii(mesh: TriangleMesh): string {
  const lines: string[] = [];
  for (let v = 0; v < mesh.positions.length / 3; v++) {
    const values = [...mesh.positions.subarray(v * 3, v * 3 + 3), ...(mesh.normals ? mesh.normals.subarray(v * 3, v * 3 + 3) : [])];
    lines.push(`${values.map(f32).join(' ')} 255`);
  }
  for (let t = 0; t < mesh.indices.length / 3; t++) lines.push(`3 ${mesh.indices.subarray(t * 3, t * 3 + 3).join(' ')}`);
  lines.push('1 0.5', '0');
  return plyHeader(mesh, 'ascii') + lines.join('\n') + '\n';
}

function plyBinary(mesh: TriangleMesh, little: boolean): Uint8Array {
  const header = new TextEncoder().encode(plyHeader(mesh, little ? 'binary_little_endian' : 'binary_big_endian'));
  const vertexCount = mesh.positions.length / 3;
  const perVertex = (mesh.normals ? 24 : 12) + 1;
  const out = new Uint8Array(header.length + vertexCount * perVertex + (mesh.indices.length / 3) * 13 + 5 + 1);
  out.set(header);
  const view = new DataView(out.buffer);
  let o = header.length;
  for (let v = 0; v < vertexCount; v++) {
    for (let k = 0; k < 3; k++, o += 4) view.setFloat32(o, mesh.positions[v * 3 + k], little);
    if (mesh.normals) for (let k = 0; k < 3; k++, o += 4) view.setFloat32(o, mesh.normals[v * 3 + k], little);
    view.setUint8(o++, 255);
  }
  for (let t = 0; t < mesh.indices.length / 3; t++) {
    view.setUint8(o++, 3);
    for (let k = 0; k < 3; k++, o += 4) view.setInt32(o, mesh.indices[t * 3 + k], little);
  }
  view.setUint8(o++, 1);
  view.setFloat32(o, 0.5, little);
  return out;
}

function gltfDocument(mesh: TriangleMesh, placeNodes: (doc: Document, make: () => Node) => Node[]): Document {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const prim = doc.createPrimitive()
    .setAttribute('POSITION', doc.createAccessor().setType('VEC3').setArray(mesh.positions.slice()).setBuffer(buffer))
    .setIndices(doc.createAccessor().setType('SCALAR').setArray(Uint16Array.from(mesh.indices)).setBuffer(buffer));
  if (mesh.normals) prim.setAttribute('NORMAL', doc.createAccessor().setType('VEC3').setArray(mesh.normals.slice()).setBuffer(buffer));
  const gltfMesh = doc.createMesh('icosphere').addPrimitive(prim);
  const scene = doc.createScene('scene');
  for (const node of placeNodes(doc, () => doc.createNode().setMesh(gltfMesh))) scene.addChild(node);
  doc.getRoot().setDefaultScene(scene);
  return doc;
}

async function embeddedGltf(io: WebIO, doc: Document): Promise<string> {
  const { json, resources } = await io.writeJSON(doc);
  for (const buffer of json.buffers ?? []) {
    const bytes = resources[buffer.uri!];
    buffer.uri = `data:application/octet-stream;base64,${Buffer.from(bytes).toString('base64')}`;
  }
  return JSON.stringify(json);
}

async function main(): Promise<void> {
  const io = new WebIO().registerExtensions([KHRDracoMeshCompression]).registerDependencies({
    'draco3d.encoder': await draco3d.createEncoderModule({}),
    'draco3d.decoder': await draco3d.createDecoderModule({}),
  });
  const write = (name: string, data: string | Uint8Array) => writeFileSync(new URL(name, OUT), data);
  for (const smooth of [false, true]) {
    const mesh = icosphere(1, smooth);
    const tag = smooth ? 'smooth' : 'flat';
    write(`ico-${tag}.obj`, obj(mesh));
    write(`ico-${tag}-ascii.ply`, plyAscii(mesh));
    write(`ico-${tag}-le.ply`, plyBinary(mesh, true));
    write(`ico-${tag}-be.ply`, plyBinary(mesh, false));
    const single = () => gltfDocument(mesh, (_doc, make) => [make()]);
    write(`ico-${tag}.gltf`, await embeddedGltf(io, single()));
    write(`ico-${tag}.glb`, await io.writeBinary(single()));
    const compressed = single();
    compressed.createExtension(KHRDracoMeshCompression).setRequired(true).setEncoderOptions({
      method: KHRDracoMeshCompression.EncoderMethod.EDGEBREAKER,
      quantizationBits: { POSITION: 16, NORMAL: 12 },
    });
    write(`ico-${tag}-draco.glb`, await io.writeBinary(compressed));
  }
  // Node transforms: one instance translated and scaled, one rotated 90 degrees
  // about +z under a translated parent (tests compose them by hand).
  const nodes = gltfDocument(icosphere(1, true), (doc, make) => [
    make().setTranslation([2, 0, 0]).setScale([1, 2, 1]),
    doc.createNode('parent').setTranslation([0, 3, 0]).addChild(make().setRotation([0, 0, Math.SQRT1_2, Math.SQRT1_2])),
  ]);
  write('ico-nodes.gltf', await embeddedGltf(io, nodes));
  write('ico-padded.ply', encodePly(padded()));
}

/** The coarse smooth icosphere with a dense one of radius 0.5 hidden inside it. */
function padded(): TriangleMesh {
  const outer = icosphere(1, true);
  const inner = icosphere(6, true);
  const join = <T extends Float32Array | Uint32Array>(a: T, b: T, out: T): T => (out.set(a), out.set(b, a.length), out);
  const n = outer.positions.length + inner.positions.length;
  return {
    positions: join(outer.positions, inner.positions.map((x) => x * 0.5), new Float32Array(n)),
    normals: join(outer.normals!, inner.normals!, new Float32Array(n)),
    indices: join(outer.indices, inner.indices.map((v) => v + outer.positions.length / 3), new Uint32Array(outer.indices.length + inner.indices.length)),
  };
}

await main();
