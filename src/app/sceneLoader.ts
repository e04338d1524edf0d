/**
 * The one path every scene load takes (file, drop, share link, example, and
 * the maps and models a scene names): read, validate and decode everything
 * first, and only when all of it succeeded replace the scene. Any failure is
 * rejected and changes nothing: not the scene, camera, selection or undo
 * history, and not the accumulated samples.
 */
import { AssetError } from '../scene/assetError';
import { loadSceneAssets, NO_ASSETS, type SceneAssets } from '../scene/assets';
import { SceneError, type SafeParseResult, type SceneIssue } from '../scene/schema';
import type { Scene } from '../scene/types';

export type AssetResult = { ok: true; assets: SceneAssets } | { ok: false; issues: SceneIssue[] };

/** The user's files opened or dropped together with a scene file, by file name. */
export type CompanionFiles = ReadonlyMap<string, Blob>;

/**
 * Decodes the maps and models a scene names, from the files opened with it
 * (matched by file name, without folders) or those already loaded (`known`).
 * A file missing or failing to decode is an issue at the scene path that
 * names it (`environment.map: "sky.hdr": ...`), and the load is rejected.
 */
export async function resolveAssets(scene: Scene, files: CompanionFiles, known: SceneAssets = NO_ASSETS): Promise<AssetResult> {
  const read = async (name: string) => {
    const file = files.get(name) ?? files.get(baseName(name));
    if (!file) throw new AssetError(`not opened: open or drop it together with the scene file`);
    return new Uint8Array(await file.arrayBuffer());
  };
  try {
    return { ok: true, assets: await loadSceneAssets(scene, read, known) };
  } catch (error) {
    if (error instanceof SceneError) return { ok: false, issues: error.issues };
    throw error;
  }
}

export const baseName = (name: string) => name.slice(name.replace(/\\/g, '/').lastIndexOf('/') + 1);

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
