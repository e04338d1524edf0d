/**
 * The files a scene file names (environment maps, meshes), read from disk
 * relative to the scene file's folder, as the format says.
 */
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import { materialTextures } from '../materials/registry';
import type { SceneAssets } from '../scene/assets';
import type { Scene } from '../scene/types';

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
  const folder = path.dirname(path.resolve(sceneFile));
  const files: Record<string, Uint8Array> = {};
  const assets = await loadSceneAssets(scene, async (name) => {
    const bytes = new Uint8Array(await readFile(path.resolve(folder, name)));
    files[name] = bytes;
    return bytes;
  });
  return { files, assets };
}

/** Whether the scene names any file (a mesh's textures come with the mesh; the ground's alone). */
export function namesFiles(scene: Scene): boolean {
  const groundTextured = scene.ground !== null && materialTextures(scene.ground.material).length > 0;
  return scene.meshes.length > 0 || (scene.environment !== null && 'map' in scene.environment) || groundTextured;
}
