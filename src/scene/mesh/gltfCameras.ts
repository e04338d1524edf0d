/**
 * The cameras of a glTF 2.0 file (`.gltf` JSON or `.glb`), each placed by
 * the first node of the file's default scene (else its first) that names
 * it, with that node's world transform: the same space the mesh decoder
 * (gltf.ts) puts the triangles in. Only the JSON is read (no buffers), so
 * this is cheap and independent of how the meshes are compressed. Pure.
 */
import { mat4 } from 'gl-matrix';
import { AssetError } from '../assetError';

export interface GltfCamera {
  /** Its index in the file's `cameras`. */
  index: number;
  name: string;
  type: 'perspective' | 'orthographic';
  /** Perspective: the vertical field of view in radians. */
  yfov?: number;
  /** Perspective: width / height, when the file gives it. */
  aspectRatio?: number;
  /**
   * Column-major world transform of the first node naming the camera (it
   * looks down its local -z, up its local +y); null when no node of the
   * scene uses the camera.
   */
  world: Float64Array | null;
}

interface GltfNode {
  camera?: number;
  children?: number[];
  matrix?: number[];
  translation?: number[];
  rotation?: number[];
  scale?: number[];
}

const GLB_MAGIC = 0x46546c67; // "glTF"
const JSON_CHUNK = 0x4e4f534a; // "JSON"

/** The glTF JSON document of a `.glb` (binary) or `.gltf` file. */
export function gltfDocument(bytes: Uint8Array, binary: boolean): Record<string, unknown> {
  let text: string;
  if (binary) {
    if (bytes.length < 20) throw new AssetError('not a glTF binary file (too short)');
    const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    if (view.getUint32(0, true) !== GLB_MAGIC) throw new AssetError('not a glTF binary file (no "glTF" magic)');
    const length = view.getUint32(12, true);
    if (view.getUint32(16, true) !== JSON_CHUNK || 20 + length > bytes.length) throw new AssetError('not a glTF binary file (no JSON chunk)');
    text = new TextDecoder().decode(bytes.subarray(20, 20 + length));
  } else {
    text = new TextDecoder().decode(bytes);
  }
  let json: unknown;
  try {
    json = JSON.parse(text);
  } catch (error) {
    throw new AssetError(`the glTF JSON is invalid (${(error as Error).message})`);
  }
  if (typeof json !== 'object' || json === null || Array.isArray(json)) throw new AssetError('the glTF JSON is not an object');
  return json as Record<string, unknown>;
}

/** Every camera of the file, in the order of its `cameras` array. */
export function readGltfCameras(bytes: Uint8Array, binary: boolean): GltfCamera[] {
  const doc = gltfDocument(bytes, binary);
  const cameras = Array.isArray(doc.cameras) ? (doc.cameras as Record<string, unknown>[]) : [];
  const worlds = cameraWorlds(doc);
  return cameras.map((camera, index) => describeCamera(camera ?? {}, index, worlds.get(index) ?? null));
}

function describeCamera(camera: Record<string, unknown>, index: number, world: Float64Array | null): GltfCamera {
  const name = typeof camera.name === 'string' ? camera.name : '';
  if (camera.type !== 'perspective') return { index, name, type: 'orthographic', world };
  const p = (camera.perspective ?? {}) as Record<string, unknown>;
  const yfov = typeof p.yfov === 'number' ? p.yfov : NaN;
  const aspectRatio = typeof p.aspectRatio === 'number' ? p.aspectRatio : undefined;
  return { index, name, type: 'perspective', yfov, ...(aspectRatio !== undefined ? { aspectRatio } : {}), world };
}

/** Camera index -> the world matrix of the first node (depth first, in the scene's order) that names it. */
function cameraWorlds(doc: Record<string, unknown>): Map<number, Float64Array> {
  const nodes = Array.isArray(doc.nodes) ? (doc.nodes as GltfNode[]) : [];
  const scenes = Array.isArray(doc.scenes) ? (doc.scenes as { nodes?: number[] }[]) : [];
  const sceneIndex = typeof doc.scene === 'number' ? doc.scene : 0;
  const roots = scenes[sceneIndex]?.nodes ?? [];
  const worlds = new Map<number, Float64Array>();
  const visiting = new Set<number>();
  const visit = (index: number, parent: Float64Array) => {
    const node = nodes[index];
    // A cycle or a dangling index is a broken file; the mesh decoder reports it, here it is skipped.
    if (!node || typeof node !== 'object' || visiting.has(index)) return;
    visiting.add(index);
    const world = mat4.multiply(new Float64Array(16), parent, localMatrix(node)) as Float64Array;
    if (typeof node.camera === 'number' && !worlds.has(node.camera)) worlds.set(node.camera, world);
    for (const child of node.children ?? []) visit(child, world);
    visiting.delete(index);
  };
  const identity = mat4.identity(new Float64Array(16)) as Float64Array;
  for (const root of roots) visit(root, identity);
  return worlds;
}

/** A node's local transform: its `matrix`, else translation * rotation * scale (glTF's rule). */
function localMatrix(node: GltfNode): Float64Array {
  const out = new Float64Array(16);
  if (isNumbers(node.matrix, 16)) return mat4.copy(out, node.matrix) as Float64Array;
  const t = isNumbers(node.translation, 3) ? node.translation : [0, 0, 0];
  const r = isNumbers(node.rotation, 4) ? node.rotation : [0, 0, 0, 1];
  const s = isNumbers(node.scale, 3) ? node.scale : [1, 1, 1];
  return mat4.fromRotationTranslationScale(out, r as [number, number, number, number], t as [number, number, number], s as [number, number, number]) as Float64Array;
}

function isNumbers(value: unknown, length: number): value is number[] {
  return Array.isArray(value) && value.length === length && value.every((v) => typeof v === 'number' && Number.isFinite(v));
}
