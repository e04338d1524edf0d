/**
 * Where a newly added model goes on the page: the fitting and framing math
 * is src/scene/modelScene.ts, shared with the command line's model scenes;
 * here it is fitted to the page's current scene (its camera and ground).
 * Pure: no DOM, no GL.
 */
import { fitMeshToView, type MeshFit } from '../scene/modelScene';
import type { Scene, TriangleMesh } from '../scene/types';

export { frameCamera, looksZUp, worldBoundingSphere, type MeshFit } from '../scene/modelScene';

/** The model in front of the scene's camera, on its ground (or centred on the target when it has none). */
export function fitMesh(data: TriangleMesh, fileName: string, scene: Scene): MeshFit {
  return fitMeshToView(data, fileName, scene.camera, scene.ground ? scene.ground.height : null);
}
