/**
 * The user's own files a scene needs: the maps, models and texture images
 * it names (not the page's bundled maps), and what its models read beside
 * themselves (a .gltf's .bin and images, an OBJ's .mtl: companionFiles.ts).
 * The autosave keeps these; the share link, which cannot carry them, names them.
 */
import { assetReferences, type SceneAssets } from '../scene/assets';
import type { Scene } from '../scene/types';
import { bundledMapName } from './bundledMaps';
import { meshCompanions } from './companionFiles';

export function userFiles(scene: Scene, assets: SceneAssets): string[] {
  const named = assetReferences(scene)
    .filter((ref) => !(ref.kind === 'map' && bundledMapName(ref.file)))
    .map((ref) => ref.file);
  const beside = scene.meshes.flatMap((mesh) => meshCompanions(mesh.file, assets.meshes.get(mesh.file)));
  return [...new Set([...named, ...beside])];
}
