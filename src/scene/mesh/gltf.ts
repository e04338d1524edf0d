/**
 * glTF 2.0 (`.gltf` and `.glb`, Draco-compressed included) through
 * glTF-Transform: every triangle primitive (TRIANGLES, TRIANGLE_STRIP,
 * TRIANGLE_FAN) of the default scene (else the first), with its node's world
 * transform applied, merged into one mesh. Smooth when every primitive has
 * NORMAL; texture coordinates TEXCOORD_0 (and TEXCOORD_1) as stored when
 * every primitive has them (normalized integer accessors de-quantized);
 * TANGENT, through the node's matrix, when a primitive of a smooth mesh has
 * it (never computed here: see tangents.ts).
 * Materials, textures, skins and morph targets are ignored.
 *
 * A `.gltf` may name external buffers (`"uri": "mesh.bin"`): they are read
 * through `resolveResource` (the CLI resolves them relative to the file);
 * without it, such a file is rejected with an error saying so. External
 * images are never read (materials are ignored).
 */
import { WebIO, type Document, type Node, type Primitive } from '@gltf-transform/core';
import { KHRONOS_EXTENSIONS } from '@gltf-transform/extensions';
import { AssetError } from '../assetError';
import type { TriangleMesh } from '../types';
import { finalizeMesh } from './finalize';
import { applyMatrix, applyMatrixToTangents, type Mat4 } from './transform';

export type ResourceResolver = (uri: string) => Promise<Uint8Array>;

type GltfJson = {
  extensionsUsed?: string[];
  buffers?: { uri?: string }[];
  images?: { uri?: string }[];
};

const DRACO = 'KHR_draco_mesh_compression';
let dracoDecoder: Promise<unknown> | null = null;

/** The Draco decoder (WebAssembly), loaded once and only for files that need it. */
function loadDracoDecoder(): Promise<unknown> {
  dracoDecoder ??= (async () => {
    const draco = await import('draco3dgltf');
    const inNode = typeof process !== 'undefined' && !!process.versions?.node;
    // In a browser the .wasm is a bundled asset handed over as bytes (no MIME or path guessing).
    const options = inNode ? {} : { wasmBinary: await (await import('./dracoWasm')).dracoWasmBinary() };
    return (draco.default ?? draco).createDecoderModule(options);
  })();
  dracoDecoder.catch(() => (dracoDecoder = null)); // a failed load may be retried
  return dracoDecoder;
}

async function createIO(json: GltfJson): Promise<WebIO> {
  const io = new WebIO().registerExtensions(KHRONOS_EXTENSIONS);
  if (!json.extensionsUsed?.includes(DRACO)) return io;
  try {
    return io.registerDependencies({ 'draco3d.decoder': await loadDracoDecoder() });
  } catch (error) {
    // In a page whose Content-Security-Policy lacks 'wasm-unsafe-eval', WebAssembly cannot compile.
    throw new AssetError(`the file is Draco-compressed and the Draco decoder (WebAssembly) cannot run here: ${(error as Error).message}`);
  }
}

export async function decodeGltf(bytes: Uint8Array, binary: boolean, resolveResource?: ResourceResolver): Promise<TriangleMesh> {
  let document: Document;
  try {
    if (binary) {
      const json = glbJson(bytes);
      document = await (await createIO(json)).readBinary(bytes);
    } else {
      const json = parseJson(bytes);
      const resources = await externalResources(json, resolveResource);
      document = await (await createIO(json)).readJSON({ json: json as never, resources });
    }
  } catch (error) {
    if (error instanceof AssetError) throw error;
    throw new AssetError(`not a valid glTF file: ${(error as Error).message}`);
  }
  return collectTriangles(document);
}

function parseJson(bytes: Uint8Array): GltfJson {
  try {
    const json = JSON.parse(new TextDecoder().decode(bytes)) as unknown;
    if (typeof json !== 'object' || json === null || !('asset' in json)) throw new Error('no "asset" object');
    return json as GltfJson;
  } catch (error) {
    throw new AssetError(`not a valid glTF file: ${(error as Error).message}`);
  }
}

/** The JSON chunk of a GLB, to see which extensions it uses before decoding. */
function glbJson(bytes: Uint8Array): GltfJson {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (bytes.length < 20 || view.getUint32(0, true) !== 0x46546c67) throw new AssetError('not a GLB file (no "glTF" magic)');
  const length = view.getUint32(12, true);
  if (view.getUint32(16, true) !== 0x4e4f534a || 20 + length > bytes.length) throw new AssetError('corrupt GLB file (bad JSON chunk)');
  return parseJson(bytes.subarray(20, 20 + length));
}

async function externalResources(json: GltfJson, resolve?: ResourceResolver): Promise<Record<string, Uint8Array<ArrayBuffer>>> {
  const resources: Record<string, Uint8Array<ArrayBuffer>> = {};
  const external = (uri?: string): uri is string => typeof uri === 'string' && !uri.startsWith('data:');
  for (const image of json.images ?? []) if (external(image.uri)) resources[image.uri] = new Uint8Array(0);
  for (const buffer of json.buffers ?? []) {
    if (!external(buffer.uri)) continue;
    if (!resolve) throw new AssetError(`the glTF names an external buffer "${buffer.uri}", which cannot be read here: use a .glb or embedded (data:) buffers`);
    try {
      resources[buffer.uri] = new Uint8Array(await resolve(buffer.uri));
    } catch (error) {
      throw new AssetError(`cannot read the glTF's buffer "${buffer.uri}": ${(error as Error).message}`);
    }
  }
  return resources;
}

const TRIANGLES = 4;
const TRIANGLE_STRIP = 5;
const TRIANGLE_FAN = 6;

function collectTriangles(document: Document): TriangleMesh {
  const root = document.getRoot();
  const scene = root.getDefaultScene() ?? root.listScenes()[0];
  if (!scene) throw new AssetError('the glTF has no scene');
  const primitives: { primitive: Primitive; matrix: Mat4 }[] = [];
  scene.traverse((node: Node) => {
    const mesh = node.getMesh();
    if (!mesh) return;
    for (const primitive of mesh.listPrimitives()) {
      if ([TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN].includes(primitive.getMode())) primitives.push({ primitive, matrix: node.getWorldMatrix() as unknown as Mat4 });
    }
  });
  if (primitives.length === 0) throw new AssetError('the file has no triangles (no triangle primitive in its scene)');
  const every = (semantic: string) => primitives.every(({ primitive }) => primitive.getAttribute(semantic) !== null);
  const smooth = every('NORMAL');
  const positions: number[] = [];
  const normals: number[] | null = smooth ? [] : null;
  const uvs: number[] | null = every('TEXCOORD_0') ? [] : null;
  const uvs1: number[] | null = every('TEXCOORD_1') ? [] : null;
  // glTF ignores TANGENT without NORMAL; primitives without one get zeros (none given).
  const tangents: number[] | null = smooth && primitives.some(({ primitive }) => primitive.getAttribute('TANGENT') !== null) ? [] : null;
  const indices: number[] = [];
  for (const { primitive, matrix } of primitives) {
    appendPrimitive(primitive, matrix, positions, normals, indices);
    if (tangents) appendTangents(primitive, matrix, tangents);
    if (uvs) appendVec2s(primitive, 'TEXCOORD_0', uvs);
    if (uvs1) appendVec2s(primitive, 'TEXCOORD_1', uvs1);
  }
  return finalizeMesh({ positions, normals, indices, uvs, uvs1, tangents });
}

/** A primitive's TANGENT (xyz, w) through its node's matrix, or zeros (none given) for each vertex when it has none. */
function appendTangents(primitive: Primitive, matrix: Mat4, out: number[]): void {
  const accessor = primitive.getAttribute('TANGENT');
  const count = primitive.getAttribute('POSITION')!.getCount();
  if (!accessor) {
    for (let i = 0; i < count * 4; i++) out.push(0);
    return;
  }
  if (accessor.getCount() !== count) throw new AssetError(`a glTF primitive has ${accessor.getCount()} TANGENT for ${count} vertices`);
  if (accessor.getElementSize() !== 4) throw new AssetError(`a glTF primitive's TANGENT has ${accessor.getElementSize()} components, not 4 (VEC4)`);
  const local = new Float64Array(count * 4);
  const element = [0, 0, 0, 0];
  for (let i = 0; i < count; i++) {
    accessor.getElement(i, element); // de-quantizes normalized integer data
    for (let k = 0; k < 4; k++) local[i * 4 + k] = element[k];
  }
  const world = applyMatrixToTangents(matrix, local);
  for (let i = 0; i < count * 4; i++) out.push(world[i]);
}

/** A primitive's texture coordinates as stored (normalized integers de-quantized), one pair per vertex of its POSITION. */
function appendVec2s(primitive: Primitive, semantic: string, out: number[]): void {
  const accessor = primitive.getAttribute(semantic)!;
  const count = primitive.getAttribute('POSITION')!.getCount();
  if (accessor.getCount() !== count) throw new AssetError(`a glTF primitive has ${accessor.getCount()} ${semantic} for ${count} vertices`);
  const element = [0, 0];
  for (let i = 0; i < count; i++) {
    accessor.getElement(i, element); // de-quantizes normalized integer data
    out.push(element[0], element[1]);
  }
}

function appendPrimitive(primitive: Primitive, matrix: Mat4, positions: number[], normals: number[] | null, indices: number[]): void {
  const position = primitive.getAttribute('POSITION');
  if (!position) throw new AssetError('a glTF triangle primitive has no POSITION');
  const base = positions.length / 3;
  const count = position.getCount();
  const local = readVec3s(position);
  const normal = normals ? readVec3s(primitive.getAttribute('NORMAL')!) : null;
  const world = applyMatrix(matrix, local, normal);
  for (let i = 0; i < count * 3; i++) positions.push(world.positions[i]);
  if (normals && world.normals) for (let i = 0; i < count * 3; i++) normals.push(world.normals[i] ?? 0);
  const order = primitiveIndices(primitive, count);
  // A mirroring node transform flips the winding; glTF says to flip it back.
  const flip = world.mirrored;
  for (let t = 0; t + 2 < order.length; t += 3) {
    indices.push(base + order[t], base + order[flip ? t + 2 : t + 1], base + order[flip ? t + 1 : t + 2]);
  }
}

function readVec3s(accessor: NonNullable<ReturnType<Primitive['getAttribute']>>): Float64Array {
  const out = new Float64Array(accessor.getCount() * 3);
  const element = [0, 0, 0];
  for (let i = 0; i < accessor.getCount(); i++) {
    accessor.getElement(i, element); // de-quantizes normalized integer data
    out[i * 3] = element[0];
    out[i * 3 + 1] = element[1];
    out[i * 3 + 2] = element[2];
  }
  return out;
}

/** Triangle list indices (3 per triangle) for any triangle mode; out-of-range indices are left for finalizeMesh. */
function primitiveIndices(primitive: Primitive, vertexCount: number): number[] {
  const accessor = primitive.getIndices();
  const raw = accessor ? Array.from(accessor.getArray() ?? []) : Array.from({ length: vertexCount }, (_, i) => i);
  for (const index of raw) {
    if (index >= vertexCount) throw new AssetError(`a glTF primitive references vertex ${index}, but it has ${vertexCount} vertices`);
  }
  const mode = primitive.getMode();
  if (mode === TRIANGLES) return raw.slice(0, raw.length - (raw.length % 3));
  const out: number[] = [];
  for (let i = 2; i < raw.length; i++) {
    if (mode === TRIANGLE_FAN) out.push(raw[0], raw[i - 1], raw[i]);
    else if (i % 2 === 0) out.push(raw[i - 2], raw[i - 1], raw[i]);
    else out.push(raw[i - 1], raw[i - 2], raw[i]);
  }
  return out;
}
