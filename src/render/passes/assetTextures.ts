/**
 * The GPU copies of a scene's decoded files: the environment map (image and
 * sampling distribution) and the BVH over the meshes' triangles, in groups
 * (src/render/bvh/groups.ts): the world-space copies of meshes not
 * instanced, and a shared file's object-space triangles once for all the
 * meshes that name it, with the instance table. Each is uploaded only when
 * its inputs change (the map by identity; the BVH when a mesh's data, a
 * copied mesh's transform or the grouping changes: triangles carry their
 * mesh, not a material slot, so spheres, lights, the ground and materials
 * never rebuild it; moving an instance only rewrites the instance table;
 * the emissive-triangle table follows the emissive meshes), so other scene
 * edits re-upload nothing here; map rotation and intensity are uniforms.
 */
import { buildEnvironmentDistribution, type EnvironmentDistribution } from '../../scene/envmap';
import type { SceneAssets } from '../../scene/assets';
import { applyMatrix, inverseAffine, meshToWorldMatrix, transformMesh } from '../../scene/mesh';
import type { EnvironmentImage, Scene, TriangleMesh } from '../../scene/types';
import { buildAliasTable } from '../aliasTable';
import { BVH_TEXTURE_WIDTH, MAX_INSTANCES, buildAndPackGroups, groupMeshes, trianglesIn, type BvhMeshInput, type MeshGroups, type PackedBvh } from '../bvh';
import { INSTANCE } from '../layout/scene';
import { packRecord } from '../layout/records';
import { BvhTextures } from '../bvhTextures';
import type { MeshEmitterSlots } from '../packScene';
import { EnvironmentTextures } from '../environmentTextures';
import type { Program } from '../gl/program';
import { createDataTexture, uploadDataTexture } from '../gl/dataTexture';
import { ENVIRONMENT_UNITS, TEXTURE_UNITS } from '../gl/textureUnits';


/** Distributions by image: building one takes tens of milliseconds for a 2k map. */
const distributions = new WeakMap<EnvironmentImage, EnvironmentDistribution>();

export function environmentDistribution(image: EnvironmentImage): EnvironmentDistribution {
  let distribution = distributions.get(image);
  if (!distribution) {
    distribution = buildEnvironmentDistribution(image);
    distributions.set(image, distribution);
  }
  return distribution;
}

/**
 * What the BVH depends on besides the decoded data: the grouping and the
 * copied (world group) meshes' transforms.
 */
function bvhKey(scene: Scene, groups: MeshGroups): string {
  return JSON.stringify([groups, groups.world.map((i) => [scene.meshes[i].position, scene.meshes[i].rotation, scene.meshes[i].scale])]);
}

/** The BVH's groups of triangles (see groups.ts): the world group's copies (when any), then each shared file's triangles once. */
export function bvhInputs(scene: Scene, assets: SceneAssets): BvhMeshInput[][] {
  const data = (i: number) => assets.meshes.get(scene.meshes[i].file)!;
  return groupInputs(groupMeshes(scene, trianglesIn(assets)), (i) => transformMesh(data(i), scene.meshes[i]), data);
}

/**
 * The inputs of the BVH groups: the copies (`copy(i)`, world space) tagged
 * with their mesh, when any; then each shared file's triangles (`data(i)` of
 * its first mesh) once, untagged (its instances carry the mesh). Every
 * triangle's mesh-local material is 0 (a mesh has one material).
 */
function groupInputs(groups: MeshGroups, copy: (i: number) => TriangleMesh, data: (i: number) => TriangleMesh): BvhMeshInput[][] {
  const copies = groups.world.map((i) => ({ ...copy(i), material: 0, mesh: i }));
  return [...(copies.length > 0 ? [copies] : []), ...groups.shared.map((users) => [{ ...data(users[0]), material: 0, mesh: -1 }])];
}

/**
 * A BVH built ahead (by the page, in a worker: buildBvhAsync over
 * bvhInputs) for exactly these meshes: the next setMeshes for them takes it
 * instead of building on the calling thread. Only the latest is kept.
 */
let prebuilt: { key: string; data: TriangleMesh[]; packed: PackedBvh } | null = null;

export function offerBvh(scene: Scene, assets: SceneAssets, packed: PackedBvh): void {
  prebuilt = { key: bvhKey(scene, groupMeshes(scene, trianglesIn(assets))), data: scene.meshes.map((m) => assets.meshes.get(m.file)!), packed };
}

function takePrebuilt(key: string, data: TriangleMesh[]): PackedBvh | null {
  const ready = prebuilt;
  if (!ready || ready.key !== key || ready.data.length !== data.length || !ready.data.every((d, i) => d === data[i])) return null;
  prebuilt = null;
  return ready.packed;
}

/** Hands in the distribution of `image` built elsewhere (the page builds it in a Worker, off the main thread). */
export function rememberEnvironmentDistribution(image: EnvironmentImage, distribution: EnvironmentDistribution): void {
  distributions.set(image, distribution);
}

export class AssetTextures {
  private environment: { image: EnvironmentImage; textures: EnvironmentTextures } | null = null;
  private world: WorldMeshes | null = null;
  private bvh: {
    world: WorldMeshes;
    roots: number[];
    triangleOrder: Uint32Array;
    textures: BvhTextures;
    /** The emissive-triangle table and the emitters' slots it was made for. */
    emissive: { key: string; table: EmissiveTriangles | null };
    instances: InstanceTable | null;
  } | null = null;

  constructor(private readonly gl: WebGL2RenderingContext) {}

  /** Uploads `image` (and its distribution) unless it is the one already uploaded; null frees it. */
  setEnvironmentMap(image: EnvironmentImage | null): void {
    if (this.environment?.image === image) return;
    this.environment?.textures.dispose();
    this.environment = image ? { image, textures: new EnvironmentTextures(this.gl, image, environmentDistribution(image)) } : null;
  }

  /**
   * The scene's meshes grouped (groups.ts): the world group's meshes copied
   * into world space, each mesh's object-to-world matrix and its size (area,
   * triangles); the copies are remade only when a file, the grouping or a
   * copied mesh's transform changes.
   */
  worldMeshes(scene: Scene, assets: SceneAssets): WorldMeshes {
    const data = scene.meshes.map((mesh) => assets.meshes.get(mesh.file)!);
    const groups = groupMeshes(scene, trianglesIn(assets));
    const key = bvhKey(scene, groups);
    const toWorld = scene.meshes.map((mesh) => meshToWorldMatrix(mesh));
    const w = this.world;
    if (w && w.key === key && w.data.length === data.length && w.data.every((d, i) => d === data[i])) {
      // Only instances may have moved: their matrices and sizes are new, the copies are not.
      const sizes = w.sizes.map((size, i) => (w.meshes[i] ? size : instanceSize(data[i], toWorld[i])));
      this.world = { ...w, toWorld, sizes };
      return this.world;
    }
    const meshes = scene.meshes.map((mesh, i) => (groups.world.includes(i) ? transformMesh(data[i], mesh) : null));
    const sizes = meshes.map((m, i) => (m ? { area: meshArea(m), triangles: m.indices.length / 3 } : instanceSize(data[i], toWorld[i])));
    this.world = { key, data, groups, meshes, toWorld, sizes };
    return this.world;
  }

  /**
   * Builds and uploads the BVH of `world`, unless its meshes' data,
   * grouping and copies are unchanged (materials do not matter: the mesh
   * records give them), its instance table, and the emissive-triangle
   * table of `emitters` unless their slots are unchanged.
   */
  setMeshes(world: WorldMeshes, emitters: readonly MeshEmitterSlots[]): void {
    const emissiveKey = JSON.stringify(emitters);
    const emissive = (triangleOrder: Uint32Array) => ({ key: emissiveKey, table: emitters.length > 0 ? new EmissiveTriangles(this.gl, world, triangleOrder, emitters) : null });
    if (this.bvh && this.bvh.world.key === world.key && this.bvh.world.data === world.data) {
      this.bvh.instances?.update(instanceRecords(world, this.bvh.roots));
      if (this.bvh.emissive.key !== emissiveKey) {
        this.bvh.emissive.table?.dispose();
        this.bvh.emissive = emissive(this.bvh.triangleOrder);
      }
      this.bvh.world = world;
      return;
    }
    this.bvh?.textures.dispose();
    this.bvh?.emissive.table?.dispose();
    this.bvh?.instances?.dispose();
    this.bvh = null;
    if (world.meshes.length === 0) return;
    let packed = takePrebuilt(world.key, world.data);
    if (!packed) {
      packed = buildAndPackGroups(groupInputs(world.groups, (i) => world.meshes[i]!, (i) => world.data[i]));
    }
    const instances = world.groups.shared.length > 0 ? new InstanceTable(this.gl, instanceRecords(world, packed.roots)) : null;
    const { roots, triangleOrder } = packed;
    this.bvh = { world, roots, triangleOrder, textures: new BvhTextures(this.gl, packed), emissive: emissive(triangleOrder), instances };
  }

  /** Sets the uniforms of the uploaded data on `program` (in use). */
  setUniforms(program: Program, scene: Scene): void {
    const e = scene.environment;
    if (this.environment && e && 'map' in e) this.environment.textures.setUniforms(program, ENVIRONMENT_UNITS, e.rotation, e.intensity);
  }

  /** Binds the textures to their units for `program` (in use); leaves another unit than 0 active. */
  bind(program: Program): void {
    this.environment?.textures.bind(ENVIRONMENT_UNITS);
    this.bvh?.textures.bind(program, TEXTURE_UNITS.bvh);
    this.bvh?.emissive.table?.bind(program, TEXTURE_UNITS.emissiveTriangles);
    this.bvh?.instances?.bind(program, TEXTURE_UNITS.instances);
  }

  dispose(): void {
    this.setEnvironmentMap(null);
    this.bvh?.textures.dispose();
    this.bvh?.emissive.table?.dispose();
    this.bvh?.instances?.dispose();
    this.bvh = null;
  }
}

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
  /** Each scene mesh's world-space area and triangle count. */
  sizes: { area: number; triangles: number }[];
}

function triangleArea(p: ArrayLike<number>, i: Uint32Array, t: number): number {
  const [a, b, c] = [i[3 * t] * 3, i[3 * t + 1] * 3, i[3 * t + 2] * 3];
  const e1 = [p[b] - p[a], p[b + 1] - p[a + 1], p[b + 2] - p[a + 2]];
  const e2 = [p[c] - p[a], p[c + 1] - p[a + 1], p[c + 2] - p[a + 2]];
  return 0.5 * Math.hypot(e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]);
}

/**
 * An instance's size. Its area is computed only if read: only emitters need
 * areas, and instances never emit (groups.ts), while transforming a big
 * model's vertices on every move would cost the page tens of milliseconds.
 */
function instanceSize(data: TriangleMesh, toWorld: Float64Array): { area: number; triangles: number } {
  let area: number | undefined;
  return {
    triangles: data.indices.length / 3,
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
 * The instance table (InstanceRecord, layout/scene.ts): the world group
 * first when it is stored (identity, its triangles' own meshes), then
 * every mesh of each shared group with its matrices and mesh index.
 */
function instanceRecords(world: WorldMeshes, roots: readonly number[]): Float32Array {
  const { groups } = world;
  const identity = new Float64Array([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]);
  const entries: { toWorld: Float64Array; root: number; mesh: number }[] = [];
  if (groups.world.length > 0) entries.push({ toWorld: identity, root: roots[0], mesh: -1 });
  const firstShared = groups.world.length > 0 ? 1 : 0;
  groups.shared.forEach((users, g) => {
    for (const i of users) entries.push({ toWorld: world.toWorld[i], root: roots[firstShared + g], mesh: i });
  });
  const out = new Float32Array(entries.length * INSTANCE.texels * 4);
  entries.forEach((e, k) => out.set(packRecord(INSTANCE, { ...matrixRows(e.toWorld), root: e.root, mesh: e.mesh }), k * INSTANCE.texels * 4));
  return out;
}

/** The rows (3x4) of an affine column-major matrix and of its inverse, as InstanceRecord fields. */
function matrixRows(m: Float64Array): Record<string, number[]> {
  const row = (a: ArrayLike<number>, r: number) => [a[r], a[4 + r], a[8 + r], a[12 + r]];
  const inv = inverseAffine(m);
  return {
    toObjectX: row(inv, 0), toObjectY: row(inv, 1), toObjectZ: row(inv, 2),
    toWorldX: row(m, 0), toWorldY: row(m, 1), toWorldZ: row(m, 2),
  };
}

/** The instance table as a one-row RGBA32F texture (scene/layout.glsl uInstances), and its count. */
class InstanceTable {
  private readonly texture: WebGLTexture;
  private count = 0;

  constructor(private readonly gl: WebGL2RenderingContext, records: Float32Array) {
    this.texture = createDataTexture(gl, MAX_INSTANCES * INSTANCE.texels, 1);
    this.update(records);
  }

  update(records: Float32Array): void {
    const gl = this.gl;
    this.count = records.length / (INSTANCE.texels * 4);
    uploadDataTexture(gl, this.texture, records.length / 4, 1, records);
  }

  bind(program: Program, unit: number): void {
    this.gl.activeTexture(this.gl.TEXTURE0 + unit);
    this.gl.bindTexture(this.gl.TEXTURE_2D, this.texture);
    program.setUniforms({ uInstances: unit, uInstanceCount: this.count }, { uInstances: 'sampler2D', uInstanceCount: 'int' });
  }

  dispose(): void {
    this.gl.deleteTexture(this.texture);
  }
}

/**
 * The emissive triangles as a texture for lights/mesh_emitter.glsl: slot
 * `first + k` of a mesh's range holds (BVH index of its triangle k, alias
 * threshold, BVH index of the alias triangle, 0) of a per-mesh alias table
 * that picks triangles in proportion to their area.
 */
class EmissiveTriangles {
  private readonly texture: WebGLTexture;

  constructor(
    private readonly gl: WebGL2RenderingContext,
    world: WorldMeshes,
    triangleOrder: Uint32Array,
    emitters: readonly MeshEmitterSlots[],
  ) {
    const bvhIndex = new Uint32Array(triangleOrder.length);
    triangleOrder.forEach((input, j) => (bvhIndex[input] = j));
    // Emissive meshes are in the world group, the first: its inputs are its meshes' triangles in order.
    const firstInput: number[] = [];
    world.groups.world.reduce((sum, i) => ((firstInput[i] = sum), sum + world.sizes[i].triangles), 0);
    const slots = emitters.reduce((n, e) => Math.max(n, e.first + e.count), 0);
    const width = BVH_TEXTURE_WIDTH;
    const data = new Float32Array(width * Math.max(1, Math.ceil(slots / width)) * 4);
    for (const e of emitters) {
      const mesh = world.meshes[e.mesh]!;
      const areas = Array.from({ length: e.count }, (_, t) => triangleArea(mesh.positions, mesh.indices, t));
      const table = buildAliasTable(areas);
      for (let k = 0; k < e.count; k++) {
        const o = (e.first + k) * 4;
        data[o] = bvhIndex[firstInput[e.mesh] + k];
        data[o + 1] = table.threshold[k];
        data[o + 2] = bvhIndex[firstInput[e.mesh] + table.alias[k]];
      }
    }
    this.texture = createDataTexture(gl, width, data.length / 4 / width, data);
  }

  bind(program: Program, unit: number): void {
    this.gl.activeTexture(this.gl.TEXTURE0 + unit);
    this.gl.bindTexture(this.gl.TEXTURE_2D, this.texture);
    program.setUniforms({ uEmissiveTriangles: unit }, { uEmissiveTriangles: 'sampler2D' });
  }

  dispose(): void {
    this.gl.deleteTexture(this.texture);
  }
}
