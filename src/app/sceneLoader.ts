/**
 * The one path every scene load takes (file, drop, share link, example, and
 * later the models and maps a scene names): read and validate everything
 * first, and only when all of it succeeded replace the scene. Any failure is
 * rejected and changes nothing: not the scene, camera, selection or undo
 * history, and not the accumulated samples.
 */
import type { SafeParseResult, SceneIssue } from '../scene/schema';
import type { Scene } from '../scene/types';

export type AssetResult = { ok: true } | { ok: false; issues: SceneIssue[] };

/**
 * Loads (decodes, uploads nothing yet) the user files a scene names. The
 * mesh and environment-map loaders plug in here: a file that fails to load
 * returns its issues (e.g. `meshes[0].file: ...`) and the whole load is
 * rejected. Scenes name no files yet, so the default resolves nothing.
 */
export type AssetResolver = (scene: Scene) => Promise<AssetResult>;
export const noAssets: AssetResolver = async () => ({ ok: true });

export class SceneLoader {
  private latest = 0;

  constructor(
    private readonly apply: (scene: Scene) => void,
    private readonly reject: (source: string, issues: SceneIssue[]) => void,
    private readonly resolveAssets: AssetResolver = noAssets,
  ) {}

  /**
   * Reads a scene with `read`, resolves its files, and applies it when both
   * succeeded. A request overtaken by a newer one is dropped. Returns whether
   * the scene was applied.
   */
  async open(source: string, read: () => SafeParseResult | Promise<SafeParseResult>): Promise<boolean> {
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
      assets = await this.resolveAssets(result.scene);
    } catch (error) {
      return fail([{ path: '', message: `could not be read (${(error as Error)?.message ?? String(error)})` }]);
    }
    if (!assets.ok) return fail(assets.issues);
    if (request !== this.latest) return false;
    this.apply(result.scene);
    return true;
  }
}
