/**
 * glTF 2.0 (`.gltf` and `.glb`, Draco-compressed included) through
 * glTF-Transform: every triangle primitive (TRIANGLES, TRIANGLE_STRIP,
 * TRIANGLE_FAN) of the default scene (else the first), with its node's world
 * transform applied, merged into one mesh. Smooth when every primitive has
 * NORMAL; texture coordinates TEXCOORD_0 and TEXCOORD_1 as stored (normalized
 * integer accessors de-quantized; zeros for a primitive without them, whose
 * material then must not be textured); COLOR_0 as linear RGB (white for a
 * primitive without it); TANGENT, through the node's matrix, when a
 * primitive of a smooth mesh has it (never computed here: see tangents.ts).
 * Materials, one per primitive, as gltfMaterials.ts maps them (the file's
 * materials); KHR_lights_punctual lights placed by their nodes. Skins,
 * morph targets, cameras and occlusion textures are ignored; extensions the
 * renderer does not read are listed in the mesh's warnings.
 *
 * A `.gltf` may name external buffers (`"uri": "mesh.bin"`): they are read
 * through `resolveResource` (the CLI resolves them relative to the file);
 * without it, such a file is rejected with an error saying so. External
 * images are not read here: a texture names its image by its URI (relative
 * to the file's folder), and the scene's assets read it beside the file.
 */
import { WebIO, type Document, type Material as GltfMaterial, type Node, type Primitive } from '@gltf-transform/core';
import { KHRONOS_EXTENSIONS } from '@gltf-transform/extensions';
import { AssetError } from '../assetError';
import { MAX_MESH_FILE_BYTES } from '../limits';
import type { EmbeddedImage, FileMaterial, TriangleMesh } from '../types';
import { finalizeMesh } from './finalize';
import { checkGltfReferences, ignoredExtensions } from './gltfChecks';
import { gltfLights } from './gltfLights';
import { gltfDefaultMaterial, mapGltfMaterial } from './gltfMaterials';
import { applyMatrix, applyMatrixToTangents, type Mat4 } from './transform';

export type ResourceResolver = (uri: string) => Promise<Uint8Array>;

export type GltfJson = {
  extensionsUsed?: string[];
  buffers?: { uri?: string }[];
  images?: { uri?: string; mimeType?: string; bufferView?: number }[];
  textures?: { source?: number; extensions?: Record<string, unknown> }[];
  materials?: Record<string, unknown>[];
  meshes?: { primitives?: Record<string, unknown>[] }[];
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
    throw new AssetError(`the file is Draco-compressed and the Draco decoder (WebAssembly) cannot run here (${(error as Error).message}): convert it to an uncompressed glTF first, e.g. \`npx @gltf-transform/cli copy in.glb out.glb\` (glTF-Transform decompresses Draco when it reads), or render it with the command-line renderer`);
  }
}

export async function decodeGltf(bytes: Uint8Array, binary: boolean, resolveResource?: ResourceResolver): Promise<TriangleMesh> {
  let document: Document;
  let json: GltfJson;
  try {
    if (binary) {
      json = glbJson(bytes);
      checkGltfReferences(json);
      checkGlbSelfContained(json);
      document = await (await createIO(json)).readBinary(bytes);
    } else {
      json = parseJson(bytes);
      checkGltfReferences(json);
      const resources = await externalResources(json, resolveResource);
      document = await (await createIO(json)).readJSON({ json: json as never, resources });
    }
  } catch (error) {
    if (error instanceof AssetError) throw error;
    throw new AssetError(`not a valid glTF file: ${(error as Error).message}`);
  }
  const warnings: string[] = [];
  const ignored = ignoredExtensions(json);
  if (ignored.length > 0) warnings.push(`ignores the glTF extensions ${ignored.join(', ')}`);
  const mesh = collectTriangles(document, warnings);
  const lights = gltfLights(document, warnings);
  if (lights.length > 0) mesh.lights = lights;
  if (warnings.length > 0) mesh.warnings = warnings;
  return mesh;
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
  // The header's total length, before anything is parsed (the CLI refuses such a file from its size already).
  const declared = view.getUint32(8, true);
  if (declared > MAX_MESH_FILE_BYTES) throw new AssetError(`the GLB header declares ${declared} bytes; files above ${MAX_MESH_FILE_BYTES / 2 ** 30} GiB (MAX_MESH_FILE_BYTES) are not read`);
  const length = view.getUint32(12, true);
  if (view.getUint32(16, true) !== 0x4e4f534a || 20 + length > bytes.length) throw new AssetError('corrupt GLB file (bad JSON chunk)');
  return parseJson(bytes.subarray(20, 20 + length));
}

/** glTF-Transform reads a .glb's embedded resources only: an image or buffer named by a file URI is refused by name. */
function checkGlbSelfContained(json: GltfJson): void {
  const external = [...(json.images ?? []), ...(json.buffers ?? [])].find((r) => typeof r.uri === 'string' && !r.uri.startsWith('data:'));
  if (external) throw new AssetError(`the .glb names "${external.uri}" outside itself, which is not read: embed its images and buffers, or use a .gltf beside them`);
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
      // A reader's own verdict (a buffer over MAX_MESH_FILE_BYTES) is not a missing file.
      if (error instanceof AssetError) throw new AssetError(`its buffer "${buffer.uri}": ${error.message}`);
      throw new AssetError(`its buffer "${buffer.uri}" is missing (${(error as Error).message}): a .gltf needs its .bin beside it`);
    }
  }
  return resources;
}

const TRIANGLES = 4;
const TRIANGLE_STRIP = 5;
const TRIANGLE_FAN = 6;

interface PlacedPrimitive {
  primitive: Primitive;
  matrix: Mat4;
  /** `meshes[m].primitives[p]`, for messages. */
  where: string;
}

function collectTriangles(document: Document, warnings: string[]): TriangleMesh {
  const root = document.getRoot();
  const scene = root.getDefaultScene() ?? root.listScenes()[0];
  if (!scene) throw new AssetError('the glTF has no scene');
  const meshes = root.listMeshes();
  const primitives: PlacedPrimitive[] = [];
  scene.traverse((node: Node) => {
    const mesh = node.getMesh();
    if (!mesh) return;
    mesh.listPrimitives().forEach((primitive, p) => {
      if ([TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN].includes(primitive.getMode())) {
        primitives.push({ primitive, matrix: node.getWorldMatrix() as unknown as Mat4, where: `meshes[${meshes.indexOf(mesh)}].primitives[${p}]` });
      }
    });
  });
  if (primitives.length === 0) throw new AssetError('the file has no triangles (no triangle primitive in its scene)');
  const every = (semantic: string) => primitives.every(({ primitive }) => primitive.getAttribute(semantic) !== null);
  const some = (semantic: string) => primitives.some(({ primitive }) => primitive.getAttribute(semantic) !== null);
  const smooth = every('NORMAL');
  const positions: number[] = [];
  const normals: number[] | null = smooth ? [] : null;
  const uvs: number[] | null = some('TEXCOORD_0') ? [] : null;
  const uvs1: number[] | null = some('TEXCOORD_1') ? [] : null;
  const colors: number[] | null = some('COLOR_0') ? [] : null;
  // glTF ignores TANGENT without NORMAL; primitives without one get zeros (none given).
  const tangents: number[] | null = smooth && some('TANGENT') ? [] : null;
  const indices: number[] = [];
  const materials = fileMaterialTable(document, warnings, !!colors);
  const triangleMaterials: number[] = [];
  for (const placed of primitives) {
    const { primitive, matrix } = placed;
    const before = indices.length;
    appendPrimitive(placed, positions, normals, indices);
    const material = materials.indexOf(primitive.getMaterial());
    for (let t = before; t < indices.length; t += 3) triangleMaterials.push(material);
    if (tangents) appendTangents(primitive, matrix, tangents);
    if (uvs) appendVec2s(primitive, 'TEXCOORD_0', uvs);
    if (uvs1) appendVec2s(primitive, 'TEXCOORD_1', uvs1);
    if (colors) appendColors(primitive, colors);
    checkCoordinates(placed, materials.get(material));
  }
  const fileMaterials = materials.used() ? { materials: materials.list(), images: materials.images(), triangles: triangleMaterials } : null;
  return finalizeMesh({ positions, normals, indices, uvs, uvs1, tangents, colors, fileMaterials });
}

/** A textured material needs the coordinate set it reads on every primitive that wears it. */
function checkCoordinates({ primitive, where }: PlacedPrimitive, material: FileMaterial): void {
  const semantic = `TEXCOORD_${material.uvSet}`;
  if (!primitive.getAttribute(semantic) && textureImages(material).length > 0) {
    throw new AssetError(`${where} has no ${semantic}, which its material ${JSON.stringify(material.name)} needs for its textures`);
  }
}

/** The images a file material's textures name. */
function textureImages(material: FileMaterial): string[] {
  const out: string[] = [];
  JSON.stringify(material.material, (key, value) => {
    if (key === 'image' && typeof value === 'string') out.push(value);
    return value;
  });
  return out;
}

/**
 * The file's materials, mapped when a primitive first wears one; index
 * `materials.length` of the file is glTF's default material, for
 * primitives with none. The embedded images their textures name.
 */
function fileMaterialTable(document: Document, warnings: string[], vertexColors: boolean) {
  const gltfMaterials = document.getRoot().listMaterials();
  const textures = document.getRoot().listTextures();
  const mapped = new Map<number, FileMaterial>();
  const get = (index: number): FileMaterial => {
    let material = mapped.get(index);
    if (!material) {
      const source = gltfMaterials[index];
      const where = source ? `materials[${index}]${source.getName() ? ` ${JSON.stringify(source.getName())}` : ''}` : '';
      material = source ? mapGltfMaterial(document, source, where, (m) => warnings.push(m)) : gltfDefaultMaterial();
      material.vertexColors = vertexColors;
      mapped.set(index, material);
    }
    return material;
  };
  return {
    indexOf: (m: GltfMaterial | null) => {
      const index = m ? gltfMaterials.indexOf(m) : gltfMaterials.length;
      get(index);
      return index;
    },
    get,
    /** Whether the file has materials of its own (a file without any keeps the scene's default). */
    used: () => gltfMaterials.length > 0,
    /** Every material, in the file's order (the default last); unused ones are mapped too, so indices stay the file's. */
    list: () => [...gltfMaterials.map((_, i) => get(i)), get(gltfMaterials.length)],
    images: (): Map<string, EmbeddedImage> => {
      const images = new Map<string, EmbeddedImage>();
      for (const m of mapped.values()) {
        for (const name of textureImages(m)) {
          const texture = name.startsWith('#') ? textures[Number(name.slice(1))] : undefined;
          if (texture) images.set(name, { bytes: texture.getImage() ?? new Uint8Array(0), mimeType: texture.getMimeType() });
        }
      }
      return images;
    },
  };
}

/** A primitive's COLOR_0 (VEC3 or VEC4, floats or normalized integers) as RGB, or white when it has none. */
function appendColors(primitive: Primitive, out: number[]): void {
  const accessor = primitive.getAttribute('COLOR_0');
  const count = primitive.getAttribute('POSITION')!.getCount();
  if (!accessor) {
    for (let i = 0; i < count * 3; i++) out.push(1);
    return;
  }
  if (accessor.getCount() !== count) throw new AssetError(`a glTF primitive has ${accessor.getCount()} COLOR_0 for ${count} vertices`);
  const element = [0, 0, 0, 0];
  for (let i = 0; i < count; i++) {
    accessor.getElement(i, element); // de-quantizes normalized integer data
    out.push(element[0], element[1], element[2]);
  }
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
  const accessor = primitive.getAttribute(semantic);
  const count = primitive.getAttribute('POSITION')!.getCount();
  if (!accessor) {
    for (let i = 0; i < count * 2; i++) out.push(0); // untextured (checkCoordinates)
    return;
  }
  if (accessor.getCount() !== count) throw new AssetError(`a glTF primitive has ${accessor.getCount()} ${semantic} for ${count} vertices`);
  const element = [0, 0];
  for (let i = 0; i < count; i++) {
    accessor.getElement(i, element); // de-quantizes normalized integer data
    out.push(element[0], element[1]);
  }
}

function appendPrimitive({ primitive, matrix, where }: PlacedPrimitive, positions: number[], normals: number[] | null, indices: number[]): void {
  const position = primitive.getAttribute('POSITION');
  if (!position) throw new AssetError(`${where} has no POSITION`);
  const base = positions.length / 3;
  const count = position.getCount();
  const local = readVec3s(position);
  const normal = normals ? readVec3s(primitive.getAttribute('NORMAL')!) : null;
  const world = applyMatrix(matrix, local, normal);
  for (let i = 0; i < count * 3; i++) positions.push(world.positions[i]);
  if (normals && world.normals) for (let i = 0; i < count * 3; i++) normals.push(world.normals[i] ?? 0);
  const order = primitiveIndices(primitive, count, where);
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
function primitiveIndices(primitive: Primitive, vertexCount: number, where: string): number[] {
  const accessor = primitive.getIndices();
  const raw = accessor ? Array.from(accessor.getArray() ?? []) : Array.from({ length: vertexCount }, (_, i) => i);
  for (const index of raw) {
    if (index >= vertexCount) throw new AssetError(`${where}: an index references vertex ${index}, but the primitive has ${vertexCount} vertices`);
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
