/**
 * The one path every scene load takes (file, drop, share link, example, and
 * the maps and models a scene names): read, validate and decode everything
 * first, and only when all of it succeeded replace the scene. Any failure is
 * rejected and changes nothing: not the scene, camera, selection or undo
 * history, and not the accumulated samples.
 */
import { AssetError } from '../scene/assetError';
import { assetReferences, loadSceneAssets, NO_ASSETS, type AssetReader, type SceneAssets } from '../scene/assets';
import { bundledMapBytes, bundledMapName } from './bundledMaps';
import { decodeMap } from './mapDecoder';
import { decodeImageOffThread } from '../render/images/decodeImages';
import { SceneError, type SafeParseResult, type SceneIssue } from '../scene/schema';
import type { EnvironmentImage, Scene, TriangleMesh } from '../scene/types';
import { baseName, fileKey, readUserFile } from './companionFiles';
import { decodeMeshOffThread } from './meshDecode';

export type AssetResult = { ok: true; assets: SceneAssets } | { ok: false; issues: SceneIssue[] };

/** The user's files opened or dropped together with a scene file, by file name. */
export type CompanionFiles = ReadonlyMap<string, Blob>;

/**
 * Decodes the maps and models a scene names, from the files opened with it
 * (matched by file name, without folders), the page's bundled maps
 * (`bundled/NAME.exr`) or those already loaded (`known`). A file missing or
 * failing to decode is an issue at the scene path that names it
 * (`environment.map: "sky.hdr": ...`), and the load is rejected. Maps are
 * decoded, and their distributions built, in a Worker: the page stays
 * interactive while a large map loads.
 */
export async function resolveAssets(scene: Scene, files: CompanionFiles, known: SceneAssets = NO_ASSETS): Promise<AssetResult> {
  const read = async (name: string) => {
    const key = fileKey(files, name);
    if (key !== undefined) return readUserFile(files.get(key)!);
    const bundled = bundledMapName(name);
    if (bundled) return bundledMapBytes(bundled);
    throw new AssetError(`not opened: open or drop it together with the scene or model that names it`);
  };
  const maps = await decodeMaps(scene, read, known);
  const meshes = await decodeMeshes(scene, read, files, known);
  // The models are decoded (and checked) even when the map failed: every unusable file is reported at once.
  const rest = maps.issues.length ? { ...scene, environment: null } : scene;
  try {
    const assets = await loadSceneAssets(rest, read, { maps: maps.maps, meshes, images: known.images }, decodeImageOffThread);
    return maps.issues.length ? { ok: false, issues: maps.issues } : { ok: true, assets };
  } catch (error) {
    if (error instanceof SceneError) return { ok: false, issues: [...maps.issues, ...error.issues] };
    throw error;
  }
}

/** The scene's map (if any) decoded off the main thread, with the known ones; loadSceneAssets then finds it decoded. */
async function decodeMaps(scene: Scene, read: AssetReader, known: SceneAssets): Promise<{ maps: Map<string, EnvironmentImage>; issues: SceneIssue[] }> {
  const maps = new Map(known.maps);
  const issues: SceneIssue[] = [];
  for (const ref of assetReferences(scene)) {
    if (ref.kind !== 'map' || maps.has(ref.file)) continue;
    try {
      maps.set(ref.file, await decodeMap(await read(ref.file), ref.file));
    } catch (error) {
      const message = error instanceof AssetError ? error.message : `cannot be read (${(error as Error)?.message ?? String(error)})`;
      issues.push({ path: ref.path, message: `${JSON.stringify(ref.file)}: ${message}` });
    }
  }
  return { maps, issues };
}

/**
 * The scene's models decoded in the mesh Worker, with the known ones (a
 * .gltf reads its .bin from the files opened with it). A model that fails
 * here is left out: loadSceneAssets decodes it again and reports it at its
 * scene path, as for every other file.
 */
async function decodeMeshes(scene: Scene, read: AssetReader, files: CompanionFiles, known: SceneAssets): Promise<Map<string, TriangleMesh>> {
  const meshes = new Map(known.meshes);
  for (const ref of assetReferences(scene)) {
    if (ref.kind !== 'mesh' || meshes.has(ref.file)) continue;
    try {
      meshes.set(ref.file, await decodeMeshOffThread(await read(ref.file), ref.file, files));
    } catch {
      // reported by loadSceneAssets
    }
  }
  return meshes;
}

export { baseName };

export class SceneLoader {
  private latest = 0;

  constructor(
    private readonly apply: (scene: Scene, assets: SceneAssets, files: CompanionFiles) => void,
    private readonly reject: (source: string, issues: SceneIssue[]) => void,
    /** The files already loaded (a scene naming one of them needs it opened only once). */
    private readonly known: () => SceneAssets = () => NO_ASSETS,
  ) {}

  /**
   * Reads a scene with `read`, decodes the files it names, and applies it
   * when both succeeded. A request overtaken by a newer one is dropped.
   * Returns whether the scene was applied.
   */
  async open(
    source: string,
    read: () => SafeParseResult | Promise<SafeParseResult>,
    files: CompanionFiles = new Map(),
  ): Promise<boolean> {
    const request = ++this.latest;
    const fail = (issues: SceneIssue[]) => {
      if (request === this.latest) this.reject(source, issues);
      return false;
    };
    let result: SafeParseResult;
    let assets: AssetResult;
    try {
      result = await read();
      if (!result.ok) return fail(result.issues);
      assets = await resolveAssets(result.scene, files, this.known());
    } catch (error) {
      return fail([{ path: '', message: `could not be read (${(error as Error)?.message ?? String(error)})` }]);
    }
    if (!assets.ok) return fail(assets.issues);
    if (request !== this.latest) return false;
    this.apply(result.scene, assets.assets, files);
    return true;
  }
}
