/**
 * The files a scene file names (environment maps, meshes), read from disk
 * relative to the scene file's folder, as the format says, or the page's
 * bundled maps (src/app/bundledMaps.ts: pure, no DOM) when not there.
 */
import path from 'node:path';
import { bundledMapBytes, bundledMapName } from '../app/bundledMaps';
import { assetReferences, type SceneAssets } from '../scene/assets';
import type { Scene } from '../scene/types';
import { readFileWithinLimit } from './readWithinLimit';

export interface SceneFiles {
  /** Bytes by name as written in the scene (what RenderSession.load takes). */
  files: Record<string, Uint8Array>;
  /** The same files decoded: reading them here finds every bad file before rendering starts (the CLI does it while Chromium starts). */
  assets: SceneAssets;
}

/** Reads and decodes every file `scene` names; throws SceneError naming each unusable one (`meshes[0].file: ...`). */
export async function readSceneFiles(scene: Scene, sceneFile: string): Promise<SceneFiles> {
  if (!namesFiles(scene)) return { files: {}, assets: { maps: new Map(), meshes: new Map(), images: new Map() } };
  // The decoders (three.js's EXR loader, glTF-Transform, Draco) load only
  // for scenes that need them: the CLI starts fast, and owns Ctrl-C early.
  const { loadSceneAssets } = await import('../scene/assets');
  const { decodeTextureImage } = await import('../scene/texture/decode');
  const { imageHeader } = await import('../scene/texture/header');
  // JPEG and WebP: the header is checked here, the pixels decoded by the
  // page's Chromium (the browser's own decoder, as on the page).
  const decodeImage = async (bytes: Uint8Array) => {
    const { format } = imageHeader(bytes);
    return format === 'jpeg' || format === 'webp' ? null : decodeTextureImage(bytes);
  };
  const folder = path.dirname(path.resolve(sceneFile));
  const files: Record<string, Uint8Array> = {};
  const assets = await loadSceneAssets(scene, async (name) => {
    const bytes = await readBesideOrBundled(folder, name);
    files[name] = bytes;
    return bytes;
  }, undefined, decodeImage);
  return { files, assets };
}

/**
 * A file beside the scene; a page's bundled map (`bundled/studio.exr`) that
 * is not there comes from the bundle, as on the page, so a scene the page
 * saved (or `pathtrace scene` wrote) renders here as it is. A file above
 * MAX_MESH_FILE_BYTES is refused from its size, before it is read.
 */
async function readBesideOrBundled(folder: string, name: string): Promise<Uint8Array> {
  try {
    return await readFileWithinLimit(path.resolve(folder, name));
  } catch (error) {
    const bundled = (error as NodeJS.ErrnoException).code === 'ENOENT' ? bundledMapName(name) : null;
    if (bundled === null) throw error;
    return bundledMapBytes(bundled);
  }
}

/** Whether the scene names any file (maps, meshes, texture images). */
export function namesFiles(scene: Scene): boolean {
  return assetReferences(scene).length > 0;
}
