/**
 * The files a scene names (environment maps, meshes), decoded. A `Scene`
 * keeps only the names as written; `SceneAssets` maps each name to its
 * decoded data, so the renderer can upload it. `loadSceneAssets` reads and
 * decodes them through a reader the caller provides (files beside a scene
 * file in the CLI, dropped files on the page), and reports every file it
 * cannot use as a SceneError issue at the scene path that names it.
 */
import { materialTextures } from '../materials/registry';
import { AssetError } from './assetError';
import { fileImageName, fileMaterialsOf, joinPath, resolveFileMaterials, wearsFileMaterials } from './fileMaterials';
import { decodeEnvironmentMap } from './envmap';
import { decodeMesh } from './mesh';
import { SceneError, type SceneIssue } from './schema';
import { decodeTextureImage } from './texture/decode';
import { textureImageBytes, type TextureImage } from './texture/image';
import { MAX_TEXTURE_BYTES } from './texture/limits';
import { MAX_LIGHTS, MAX_MESHES } from './limits';
import type { EnvironmentImage, Material, Scene, TriangleMesh } from './types';

export interface SceneAssets {
  maps: ReadonlyMap<string, EnvironmentImage>;
  meshes: ReadonlyMap<string, TriangleMesh>;
  /** Texture images (absent: none). */
  images?: ReadonlyMap<string, TextureImage>;
  /**
   * JPEG/WebP files whose header was checked but which are left for a
   * browser to decode (its own decoder: the CLI's Chromium decodes them);
   * a renderer needs them decoded into `images`.
   */
  encodedImages?: ReadonlyMap<string, Uint8Array>;
}

export const NO_ASSETS: SceneAssets = { maps: new Map(), meshes: new Map(), images: new Map() };

/** The files of both (`b`'s where both name one); `a` itself when `b` adds nothing. */
export function mergeAssets(a: SceneAssets, b: SceneAssets): SceneAssets {
  if (!b.maps.size && !b.meshes.size && !b.images?.size) return a;
  return {
    maps: new Map([...a.maps, ...b.maps]),
    meshes: new Map([...a.meshes, ...b.meshes]),
    images: new Map([...(a.images ?? []), ...(b.images ?? [])]),
  };
}

export type AssetKind = 'map' | 'mesh' | 'image';

/** A file a scene names, with the scene path that names it. */
export interface AssetReference {
  kind: AssetKind;
  file: string;
  path: string;
}

/** The texture images a material names, at their scene paths (`meshes[0].material.baseColor.image`). */
function imageReferences(material: Material | null, path: string): AssetReference[] {
  if (!material) return [];
  return materialTextures(material).map((t) => ({ kind: 'image', file: t.texture.image, path: `${path}.${t.path.join('.')}.image` }));
}

export function assetReferences(scene: Scene): AssetReference[] {
  const refs: AssetReference[] = [];
  if (scene.environment && 'map' in scene.environment) refs.push({ kind: 'map', file: scene.environment.map, path: 'environment.map' });
  scene.meshes.forEach((mesh, i) => refs.push({ kind: 'mesh', file: mesh.file, path: `meshes[${i}].file` }));
  if (scene.ground) refs.push(...imageReferences(scene.ground.material, 'ground.material'));
  scene.meshes.forEach((mesh, i) => refs.push(...imageReferences(mesh.material, `meshes[${i}].material`)));
  return refs;
}

/**
 * How a texture image is decoded (in the browser: off the main thread, with
 * its own JPEG/WebP decoder); null: left for a browser (encodedImages).
 */
export type ImageDecoder = (bytes: Uint8Array) => Promise<TextureImage | null>;

const tableOf = (assets: SceneAssets, kind: AssetKind): ReadonlyMap<string, unknown> =>
  kind === 'map' ? assets.maps : kind === 'mesh' ? assets.meshes : (assets.images ?? new Map());

/** Reads the bytes of a file the scene names (by the name as written); throws to report it unreadable. */
export type AssetReader = (file: string) => Promise<Uint8Array>;

/**
 * Reads and decodes every file the scene names (each once). Throws
 * SceneError with one issue per unusable file, e.g.
 * `meshes[1].file: "gem.obj": no triangles`.
 */
export async function loadSceneAssets(
  scene: Scene,
  read: AssetReader,
  known: SceneAssets = NO_ASSETS,
  decodeImage: ImageDecoder = (bytes) => decodeTextureImage(bytes),
): Promise<SceneAssets> {
  const maps = new Map<string, EnvironmentImage>();
  const meshes = new Map<string, TriangleMesh>();
  const images = new Map<string, TextureImage>();
  const encodedImages = new Map<string, Uint8Array>();
  const tables: Record<AssetKind, Map<string, unknown>> = { map: maps, mesh: meshes, image: images };
  const issues: SceneIssue[] = [];
  let imageBytes = 0;
  const load = async (ref: AssetReference, bytesOf: () => Promise<Uint8Array>) => {
    const table = tables[ref.kind];
    if (table.has(ref.file) || encodedImages.has(ref.file)) return;
    const cached = tableOf(known, ref.kind).get(ref.file);
    try {
      const bytes = cached ? null : await bytesOf();
      const value = cached ?? (await decode(ref, bytes!, decodeImage, read));
      if (value === null) {
        encodedImages.set(ref.file, bytes!);
        return;
      }
      if (ref.kind === 'image') {
        imageBytes += textureImageBytes(value as TextureImage);
        if (imageBytes > MAX_TEXTURE_BYTES) throw new AssetError(`the scene's images take more than ${MAX_TEXTURE_BYTES / 2 ** 20} MB decoded`);
      }
      table.set(ref.file, value);
    } catch (error) {
      issues.push({ path: ref.path, message: `${JSON.stringify(ref.file)}: ${describe(error)}` });
    }
  };
  for (const ref of assetReferences(scene)) await load(ref, () => read(ref.file));
  // The images of the files' own materials, once the files are decoded.
  for (const ref of fileImageReferences(scene, meshes, read)) await load(ref, ref.bytes);
  issues.push(...textureCoordinateIssues(scene, { maps, meshes, images }), ...resolvedCountIssues(scene, { maps, meshes }));
  if (issues.length > 0) throw new SceneError(issues);
  return { maps, meshes, images, ...(encodedImages.size > 0 ? { encodedImages } : {}) };
}

/**
 * The images that meshes wearing their files' own materials need, each at
 * the path of the mesh that names the file (`meshes[0].file`), with its
 * bytes: embedded in the file or read beside it.
 */
function fileImageReferences(scene: Scene, meshes: ReadonlyMap<string, TriangleMesh>, read: AssetReader): (AssetReference & { bytes: () => Promise<Uint8Array> })[] {
  const refs: (AssetReference & { bytes: () => Promise<Uint8Array> })[] = [];
  scene.meshes.forEach((mesh, i) => {
    const data = meshes.get(mesh.file);
    if (!wearsFileMaterials(mesh, data)) return;
    const own = data!.fileMaterials!;
    const names = new Set(own.materials.flatMap((m) => materialTextures(m.material).map((t) => t.texture.image)));
    for (const name of names) {
      const embedded = own.images.get(name);
      const file = fileImageName(mesh.file, name);
      const bytes = embedded ? async () => embedded.bytes : () => readBeside(read, file, mesh.file);
      refs.push({ kind: 'image', file, path: `meshes[${i}].file`, bytes });
    }
  });
  return refs;
}

/** A file a mesh file names (a .gltf's .bin or image, an OBJ's MTL): a missing one is named as such. */
async function readBeside(read: AssetReader, file: string, meshFile: string): Promise<Uint8Array> {
  try {
    return await read(file);
  } catch (error) {
    throw new AssetError(`${JSON.stringify(file)}, which ${JSON.stringify(meshFile)} names, is missing (${error instanceof Error ? error.message : String(error)})`);
  }
}

/** The renderer's tables hold MAX_MESHES meshes, one per material of a file wearing its own, and MAX_LIGHTS lights, a file's included. */
function resolvedCountIssues(scene: Scene, assets: SceneAssets): SceneIssue[] {
  const resolved = resolveFileMaterials(scene, assets).scene;
  const issues: SceneIssue[] = [];
  if (resolved.meshes.length > MAX_MESHES) issues.push({ path: 'meshes', message: `the files' own materials make ${resolved.meshes.length} meshes of one material each; at most ${MAX_MESHES} can be drawn` });
  if (resolved.lights.length > MAX_LIGHTS) issues.push({ path: 'lights', message: `with the files' lights the scene has ${resolved.lights.length} lights; at most ${MAX_LIGHTS}` });
  return issues;
}
async function decode(ref: AssetReference, bytes: Uint8Array, decodeImage: ImageDecoder, read: AssetReader): Promise<unknown> {
  if (ref.kind === 'map') return decodeEnvironmentMap(bytes, ref.file);
  if (ref.kind === 'mesh') return decodeMesh(bytes, ref.file, { resolveResource: (uri) => read(joinPath(folderOf(ref.file), decodeUri(uri))) });
  return decodeImage(bytes);
}

const folderOf = (file: string) => file.slice(0, Math.max(0, file.lastIndexOf('/')));
const decodeUri = (uri: string) => {
  try {
    return decodeURIComponent(uri);
  } catch {
    return uri;
  }
};

/** Every mesh file's warnings (what its decoder ignored), at the path of the first mesh that names it. */
export function meshWarnings(scene: Scene, assets: SceneAssets): SceneIssue[] {
  const seen = new Set<string>();
  return scene.meshes.flatMap((mesh, i) => {
    const warnings = assets.meshes.get(mesh.file)?.warnings ?? [];
    if (seen.has(mesh.file) || warnings.length === 0) return [];
    seen.add(mesh.file);
    return warnings.map((message) => ({ path: `meshes[${i}].file`, message: `${JSON.stringify(mesh.file)} ${message}` }));
  });
}

/** A textured mesh needs texture coordinates: the file's (the format's rule). */
export function textureCoordinateIssues(scene: Scene, assets: SceneAssets): SceneIssue[] {
  return scene.meshes.flatMap((mesh, i) => {
    const data = assets.meshes.get(mesh.file);
    const textured = mesh.material ? materialTextures(mesh.material) : [];
    if (!data || data.uvs || textured.length === 0) return [];
    return [{ path: `meshes[${i}].file`, message: `${JSON.stringify(mesh.file)} has no texture coordinates, which the material's ${textured[0].key} texture needs` }];
  });
}

/** The issues of a scene whose files are not all in `assets` (what a renderer must refuse). */
export function missingAssets(scene: Scene, assets: SceneAssets): SceneIssue[] {
  const fileImages = scene.meshes.flatMap((mesh, i) =>
    fileMaterialsOf(mesh, assets.meshes.get(mesh.file)).flatMap((m) => imageReferences(m.material, `meshes[${i}].file`)),
  );
  const missing = [...assetReferences(scene), ...fileImages]
    .filter((ref) => !tableOf(assets, ref.kind).has(ref.file))
    .map((ref) => ({ path: ref.path, message: `${JSON.stringify(ref.file)} is not loaded (pass it in the assets)` }));
  return missing.length > 0 ? missing : textureCoordinateIssues(scene, assets);
}

function describe(error: unknown): string {
  if (error instanceof AssetError) return error.message;
  const message = error instanceof Error ? error.message : String(error);
  return `cannot be read (${message.length > 200 ? `${message.slice(0, 200)}...` : message})`;
}
