/**
 * Prepared geometry (pure: no GL): the scene's meshes as the BVH and the
 * packer need them, between the decoded files (SceneAssets) and the upload
 * (src/render/passes/assetTextures.ts): world-space copies, groups, areas,
 * BVH inputs, the key of what a BVH was built for.
 */
import type { SceneAssets } from '../../scene/assets';
import { applyMatrix, meshToWorldMatrix, transformMesh } from '../../scene/mesh';
import type { Scene as SceneModel, TriangleMesh, Vec3 } from '../../scene/types';
import type { Box } from '../lightChoice';
import { meshBounds } from '../../scene/picking';
import { resolveFileMaterials, type RenderScene as Scene } from '../../scene/fileMaterials';
import { groupMeshes, trianglesIn, type BvhMeshInput, type MeshGroups, type PackedBvh } from '../bvh';

export interface WorldMeshes {
  /** What the copies and the BVH depend on besides `data` (bvhKey). */
  key: string;
  /** Each scene mesh's decoded file. */
  data: TriangleMesh[];
  groups: MeshGroups;
  /** Each scene mesh in world space when it is copied into the world group, null when instanced. */
  meshes: (TriangleMesh | null)[];
  /** Each scene mesh's object-to-world matrix (column-major 4x4). */
  toWorld: Float64Array[];
  /** Each scene mesh's world-space area, triangle count and bounding box. */
  sizes: MeshSize[];
  /** Each scene mesh: whether its material multiplies by its file's vertex colors (the BVH stores them only then). */
  vertexColors: boolean[];
}

export function triangleArea(p: ArrayLike<number>, i: Uint32Array, t: number): number {
  const [a, b, c] = [i[3 * t] * 3, i[3 * t + 1] * 3, i[3 * t + 2] * 3];
  const e1 = [p[b] - p[a], p[b + 1] - p[a + 1], p[b + 2] - p[a + 2]];
  const e2 = [p[c] - p[a], p[c + 1] - p[a + 1], p[c + 2] - p[a + 2]];
  return 0.5 * Math.hypot(e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]);
}

export interface MeshSize {
  area: number;
  triangles: number;
  box: Box;
}

/**
 * A mesh's world box: the box of its file's box (meshBounds, computed once
 * per file) through the column-major matrix `toWorld`, corner by corner. A
 * copy's and an instance's are the same, so the emitter-choice grid does
 * not depend on how a mesh is stored.
 */
function worldBox(data: TriangleMesh, toWorld: Float64Array): Box {
  const local = meshBounds(data);
  const min: Vec3 = [Infinity, Infinity, Infinity];
  const max: Vec3 = [-Infinity, -Infinity, -Infinity];
  for (let c = 0; c < 8; c++) {
    const p = [c & 1 ? local.max[0] : local.min[0], c & 2 ? local.max[1] : local.min[1], c & 4 ? local.max[2] : local.min[2]];
    for (let row = 0; row < 3; row++) {
      const v = toWorld[row] * p[0] + toWorld[4 + row] * p[1] + toWorld[8 + row] * p[2] + toWorld[12 + row];
      min[row] = Math.min(min[row], v);
      max[row] = Math.max(max[row], v);
    }
  }
  return { min, max };
}

/**
 * An instance's size. Its area is computed only if read: only emitters need
 * areas, and instances never emit (groups.ts), while transforming a big
 * model's vertices on every move would cost the page tens of milliseconds.
 */
function instanceSize(data: TriangleMesh, toWorld: Float64Array): MeshSize {
  let area: number | undefined;
  return {
    triangles: data.indices.length / 3,
    box: worldBox(data, toWorld),
    get area() {
      return (area ??= meshArea(data, toWorld));
    },
  };
}

/** The mesh's area, in world space through `toWorld` when given. */
function meshArea(mesh: TriangleMesh, toWorld?: Float64Array): number {
  const positions = toWorld ? applyMatrix(toWorld, mesh.positions, null).positions : mesh.positions;
  let area = 0;
  for (let t = 0; t < mesh.indices.length / 3; t++) area += triangleArea(positions, mesh.indices, t);
  return area;
}

/**
 * What the BVH depends on besides the decoded data: the grouping and the
 * copied (world group) meshes' transforms.
 */
function bvhKey(scene: Scene, groups: MeshGroups): string {
  return JSON.stringify([groups, groups.world.map((i) => [scene.meshes[i].position, scene.meshes[i].rotation, scene.meshes[i].scale]), vertexColorsOf(scene)]);
}

/** Per scene mesh, whether the BVH stores its vertex colors: its material multiplies by them. */
const vertexColorsOf = (scene: Scene): boolean[] => scene.meshes.map((m) => m.vertexColors === true);

/** The BVH's groups of triangles (see groups.ts): the world group's copies (when any), then each shared file's triangles once. */
export function bvhInputs(sceneModel: SceneModel, allAssets: SceneAssets): BvhMeshInput[][] {
  const { scene, assets } = resolveFileMaterials(sceneModel, allAssets);
  const data = (i: number) => assets.meshes.get(scene.meshes[i].file)!;
  return groupInputs(groupMeshes(scene, trianglesIn(assets)), (i) => transformMesh(data(i), scene.meshes[i]), data, vertexColorsOf(scene));
}

/**
 * The inputs of the BVH groups: the copies (`copy(i)`, world space) tagged
 * with their mesh, when any; then each shared file's triangles (`data(i)` of
 * its first mesh) once, untagged (its instances carry the mesh). Every
 * triangle's mesh-local material is 0 (a mesh has one material). A mesh's
 * vertex colors (its file's, `data(i).colors`) go in only where
 * `vertexColors[i]`: a material that does not multiply by them costs no
 * texels. The meshes sharing a file all name the same subset of it
 * (fileMaterials.ts), so they agree; the first one's flag decides.
 */
export function groupInputs(groups: MeshGroups, copy: (i: number) => TriangleMesh, data: (i: number) => TriangleMesh, vertexColors: readonly boolean[]): BvhMeshInput[][] {
  const colors = (i: number) => (vertexColors[i] ? (data(i).colors ?? null) : null);
  const copies = groups.world.map((i) => ({ ...copy(i), colors: colors(i), material: 0, mesh: i }));
  return [...(copies.length > 0 ? [copies] : []), ...groups.shared.map((users) => [{ ...data(users[0]), colors: colors(users[0]), material: 0, mesh: -1 }])];
}

/**
 * A BVH built ahead (by the page, in a worker: buildBvhAsync over
 * bvhInputs) for the meshes of one scene and its assets: given to
 * PathTracer.setScene, it is used instead of building on the calling thread
 * when the scene's meshes are still exactly those.
 */
export interface PrebuiltBvh {
  key: string;
  data: readonly TriangleMesh[];
  packed: PackedBvh;
}

export function prebuiltBvh(sceneModel: SceneModel, allAssets: SceneAssets, packed: PackedBvh): PrebuiltBvh {
  const { scene, assets } = resolveFileMaterials(sceneModel, allAssets);
  return { key: bvhKey(scene, groupMeshes(scene, trianglesIn(assets))), data: scene.meshes.map((m) => assets.meshes.get(m.file)!), packed };
}

export function prebuiltFor(prebuilt: PrebuiltBvh | undefined, world: WorldMeshes): PackedBvh | null {
  const { key, data } = world;
  if (!prebuilt || prebuilt.key !== key || prebuilt.data.length !== data.length || !prebuilt.data.every((d, i) => d === data[i])) return null;
  return prebuilt.packed;
}

/**
 * The scene's meshes grouped (groups.ts): the world group's meshes copied
 * into world space, each mesh's object-to-world matrix and its size (area,
 * triangles). The copies of `previous` (what this returned for the scene
 * before) are kept unless a file, the grouping or a copied mesh's transform
 * changed.
 */
export function prepareWorldMeshes(scene: Scene, assets: SceneAssets, previous: WorldMeshes | null = null): WorldMeshes {
  const data = scene.meshes.map((mesh) => assets.meshes.get(mesh.file)!);
  const groups = groupMeshes(scene, trianglesIn(assets));
  const key = bvhKey(scene, groups);
  const toWorld = scene.meshes.map((mesh) => meshToWorldMatrix(mesh));
  const w = previous;
  if (w && w.key === key && w.data.length === data.length && w.data.every((d, i) => d === data[i])) {
    // Only instances may have moved: their matrices and sizes are new, the copies are not.
    const sizes = w.sizes.map((size, i) => (w.meshes[i] ? size : instanceSize(data[i], toWorld[i])));
    return { ...w, toWorld, sizes };
  }
  const vertexColors = vertexColorsOf(scene);
  const meshes = scene.meshes.map((mesh, i) => (groups.world.includes(i) ? transformMesh(data[i], mesh) : null));
  const sizes = meshes.map((m, i) => (m ? { area: meshArea(m), triangles: m.indices.length / 3, box: worldBox(data[i], toWorld[i]) } : instanceSize(data[i], toWorld[i])));
  return { key, data, groups, meshes, toWorld, sizes, vertexColors };
}

