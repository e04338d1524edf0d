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
import { decodeEnvironmentMap } from './envmap';
import { decodeMesh } from './mesh';
import { SceneError, type SceneIssue } from './schema';
import { decodeTextureImage } from './texture/decode';
import { textureImageBytes, type TextureImage } from './texture/image';
import { MAX_TEXTURE_BYTES } from './texture/limits';
import type { EnvironmentImage, Material, Scene, TriangleMesh } from './types';

export interface SceneAssets {
  maps: ReadonlyMap<string, EnvironmentImage>;
  meshes: ReadonlyMap<string, TriangleMesh>;
  /** Texture images (absent: none). */
  images?: ReadonlyMap<string, TextureImage>;
}

export const NO_ASSETS: SceneAssets = { maps: new Map(), meshes: new Map(), images: new Map() };

export type AssetKind = 'map' | 'mesh' | 'image';

/** A file a scene names, with the scene path that names it. */
export interface AssetReference {
  kind: AssetKind;
  file: string;
  path: string;
}

/** The texture images a material names, at their scene paths (`meshes[0].material.baseColor.image`). */
function imageReferences(material: Material, path: string): AssetReference[] {
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

/** How a texture image is decoded (in the browser: off the main thread, with its own JPEG/WebP decoder). */
export type ImageDecoder = (bytes: Uint8Array) => Promise<TextureImage>;

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
  const tables: Record<AssetKind, Map<string, unknown>> = { map: maps, mesh: meshes, image: images };
  const issues: SceneIssue[] = [];
  let imageBytes = 0;
  for (const ref of assetReferences(scene)) {
    const table = tables[ref.kind];
    if (table.has(ref.file)) continue;
    const cached = tableOf(known, ref.kind).get(ref.file);
    try {
      const value = cached ?? (await decode(ref, await read(ref.file), decodeImage));
      if (ref.kind === 'image') {
        imageBytes += textureImageBytes(value as TextureImage);
        if (imageBytes > MAX_TEXTURE_BYTES) throw new AssetError(`the scene's images take more than ${MAX_TEXTURE_BYTES / 2 ** 20} MB decoded`);
      }
      table.set(ref.file, value);
    } catch (error) {
      issues.push({ path: ref.path, message: `${JSON.stringify(ref.file)}: ${describe(error)}` });
    }
  }
  issues.push(...textureCoordinateIssues(scene, { maps, meshes, images }));
  if (issues.length > 0) throw new SceneError(issues);
  return { maps, meshes, images };
}

async function decode(ref: AssetReference, bytes: Uint8Array, decodeImage: ImageDecoder): Promise<unknown> {
  if (ref.kind === 'map') return decodeEnvironmentMap(bytes, ref.file);
  if (ref.kind === 'mesh') return decodeMesh(bytes, ref.file);
  return decodeImage(bytes);
}

/** A textured mesh needs texture coordinates: the file's (the format's rule). */
export function textureCoordinateIssues(scene: Scene, assets: SceneAssets): SceneIssue[] {
  return scene.meshes.flatMap((mesh, i) => {
    const data = assets.meshes.get(mesh.file);
    const textured = materialTextures(mesh.material);
    if (!data || data.uvs || textured.length === 0) return [];
    return [{ path: `meshes[${i}].file`, message: `${JSON.stringify(mesh.file)} has no texture coordinates, which the material's ${textured[0].key} texture needs` }];
  });
}

/** The issues of a scene whose files are not all in `assets` (what a renderer must refuse). */
export function missingAssets(scene: Scene, assets: SceneAssets): SceneIssue[] {
  const missing = assetReferences(scene)
    .filter((ref) => !tableOf(assets, ref.kind).has(ref.file))
    .map((ref) => ({ path: ref.path, message: `${JSON.stringify(ref.file)} is not loaded (pass it in the assets)` }));
  return missing.length > 0 ? missing : textureCoordinateIssues(scene, assets);
}

function describe(error: unknown): string {
  if (error instanceof AssetError) return error.message;
  const message = error instanceof Error ? error.message : String(error);
  return `cannot be read (${message.length > 200 ? `${message.slice(0, 200)}...` : message})`;
}
