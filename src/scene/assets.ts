/**
 * The files a scene names (environment maps, meshes), decoded. A `Scene`
 * keeps only the names as written; `SceneAssets` maps each name to its
 * decoded data, so the renderer can upload it. `loadSceneAssets` reads and
 * decodes them through a reader the caller provides (files beside a scene
 * file in the CLI, dropped files on the page), and reports every file it
 * cannot use as a SceneError issue at the scene path that names it.
 */
import { AssetError } from './assetError';
import { decodeEnvironmentMap } from './envmap';
import { decodeMesh } from './mesh';
import { SceneError, type SceneIssue } from './schema';
import type { EnvironmentImage, Scene, TriangleMesh } from './types';

export interface SceneAssets {
  maps: ReadonlyMap<string, EnvironmentImage>;
  meshes: ReadonlyMap<string, TriangleMesh>;
}

export const NO_ASSETS: SceneAssets = { maps: new Map(), meshes: new Map() };

/** A file a scene names, with the scene path that names it. */
export interface AssetReference {
  kind: 'map' | 'mesh';
  file: string;
  path: string;
}

export function assetReferences(scene: Scene): AssetReference[] {
  const refs: AssetReference[] = [];
  if (scene.environment && 'map' in scene.environment) refs.push({ kind: 'map', file: scene.environment.map, path: 'environment.map' });
  scene.meshes.forEach((mesh, i) => refs.push({ kind: 'mesh', file: mesh.file, path: `meshes[${i}].file` }));
  return refs;
}

/** Reads the bytes of a file the scene names (by the name as written); throws to report it unreadable. */
export type AssetReader = (file: string) => Promise<Uint8Array>;

/**
 * Reads and decodes every file the scene names (each once). Throws
 * SceneError with one issue per unusable file, e.g.
 * `meshes[1].file: "gem.obj": no triangles`.
 */
export async function loadSceneAssets(scene: Scene, read: AssetReader, known: SceneAssets = NO_ASSETS): Promise<SceneAssets> {
  const maps = new Map<string, EnvironmentImage>();
  const meshes = new Map<string, TriangleMesh>();
  const issues: SceneIssue[] = [];
  for (const ref of assetReferences(scene)) {
    const table: Map<string, unknown> = ref.kind === 'map' ? maps : meshes;
    if (table.has(ref.file)) continue;
    const cached = ref.kind === 'map' ? known.maps.get(ref.file) : known.meshes.get(ref.file);
    if (cached) {
      table.set(ref.file, cached);
      continue;
    }
    try {
      const bytes = await read(ref.file);
      table.set(ref.file, ref.kind === 'map' ? decodeEnvironmentMap(bytes, ref.file) : await decodeMesh(bytes, ref.file));
    } catch (error) {
      issues.push({ path: ref.path, message: `${JSON.stringify(ref.file)}: ${describe(error)}` });
    }
  }
  if (issues.length > 0) throw new SceneError(issues);
  return { maps, meshes };
}

/** The issues of a scene whose files are not all in `assets` (what a renderer must refuse). */
export function missingAssets(scene: Scene, assets: SceneAssets): SceneIssue[] {
  return assetReferences(scene)
    .filter((ref) => !(ref.kind === 'map' ? assets.maps : assets.meshes).has(ref.file))
    .map((ref) => ({ path: ref.path, message: `${JSON.stringify(ref.file)} is not loaded (pass it in the assets)` }));
}

function describe(error: unknown): string {
  if (error instanceof AssetError) return error.message;
  const message = error instanceof Error ? error.message : String(error);
  return `cannot be read (${message.length > 200 ? `${message.slice(0, 200)}...` : message})`;
}
