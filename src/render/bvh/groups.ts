/**
 * Instancing: which meshes share one stored copy of their file's triangles.
 *
 * The BVH texture holds one or more triangle groups, each with its own BVH:
 * - the world group: every mesh that is not instanced, its triangles in world
 *   space (copied and transformed per mesh), as before instancing;
 * - one shared group per file named by several meshes whose materials do not
 *   emit: the file's triangles once, in object space. Each such mesh is an
 *   instance: rays are taken into object space by its world-to-object matrix
 *   (t is unchanged by an affine map), so the triangles are stored once
 *   however many meshes name the file.
 * Emissive meshes stay in the world group: light sampling picks their
 * triangles from a table of world-space triangles (lights/mesh_emitter.glsl).
 *
 * The traversal visits the instances in a loop (scene/instances.glsl), each
 * a full BVH query, so every instance costs every ray at least one node step
 * and a ray transform, and on SwiftShader a pixel quad runs each instance's
 * traversal until its slowest lane is done: measured (bench/instancing.ts),
 * K instances render at 0.64-0.80 of the path rate of K copies in one BVH.
 * So a file is instanced only where copies would cost real memory: when
 * they would store at least INSTANCE_MIN_SAVED_TRIANGLES more triangles
 * (about 12 MB of BVH texture); a smaller model is copied, which is faster.
 * The number of instances is capped (MAX_INSTANCES, the world group
 * included); meshes past the cap are copied. Scenes with no instanced file
 * compile no instance code at all.
 */
import type { SceneAssets } from '../../scene/assets';
import type { Material } from '../../scene/types';

/** What grouping reads of a scene: each mesh's file and material (null: its file's own, which emit only once resolved). */
type Scene = { meshes: readonly { file: string; material: Material | null }[] };

/** Instance records (the world group's included): the loop's most iterations per ray. */
export const MAX_INSTANCES = 8;
/** A shared file is instanced when copies would store at least this many more triangles than one copy. */
export const INSTANCE_MIN_SAVED_TRIANGLES = 100_000;

/** Triangles of a decoded file, by its name as the scene writes it (0 when not loaded). */
export type TriangleCount = (file: string) => number;

export const trianglesIn = (assets: SceneAssets): TriangleCount => (file) => (assets.meshes.get(file)?.indices.length ?? 0) / 3;

export interface MeshGroups {
  /** Scene mesh indices copied into the world group, in scene order. */
  world: number[];
  /** Per shared file, the scene mesh indices that name it (at least two), in scene order. */
  shared: number[][];
}

const emits = (scene: Scene, i: number) => {
  const e = scene.meshes[i].material?.emission;
  return !!e && e.intensity > 0 && e.color.some((c) => c > 0);
};

/**
 * Groups the scene's meshes (see above). Pure: depends only on file names,
 * materials and the files' triangle counts. `minSaved`: the threshold (tests
 * lower it to instance small models).
 */
export function groupMeshes(scene: Scene, trianglesOf: TriangleCount, minSaved = INSTANCE_MIN_SAVED_TRIANGLES): MeshGroups {
  const byFile = new Map<string, number[]>();
  scene.meshes.forEach((mesh, i) => {
    if (emits(scene, i)) return;
    const users = byFile.get(mesh.file);
    if (users) users.push(i);
    else byFile.set(mesh.file, [i]);
  });
  const shared: number[][] = [];
  const instanced = new Set<number>();
  // Room for the shared meshes' instances; one record is the world group's when any mesh is left in it.
  let room = MAX_INSTANCES;
  for (const users of byFile.values()) {
    if (users.length < 2 || (users.length - 1) * trianglesOf(scene.meshes[users[0]].file) < minSaved) continue;
    const leftInWorld = scene.meshes.length - instanced.size - users.length > 0 ? 1 : 0;
    if (users.length + leftInWorld > room) continue;
    shared.push(users);
    users.forEach((i) => instanced.add(i));
    room -= users.length;
  }
  const world = scene.meshes.map((_, i) => i).filter((i) => !instanced.has(i));
  return { world, shared };
}

/** Triangles stored for the scene's meshes: a shared file's once (the triangle limit counts these). */
export function storedTriangles(scene: Scene, trianglesOf: TriangleCount): number {
  const { world, shared } = groupMeshes(scene, trianglesOf);
  const count = (i: number) => trianglesOf(scene.meshes[i].file);
  return world.reduce((n, i) => n + count(i), 0) + shared.reduce((n, users) => n + count(users[0]), 0);
}
