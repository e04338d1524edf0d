/**
 * The GPU copies of a scene's decoded files: the environment map (image and
 * sampling distribution) and the BVH over the meshes' world-space triangles.
 * Each is uploaded only when its inputs change (the map by identity; the BVH
 * when a mesh's data, transform or material slot changes), so other scene
 * edits re-upload nothing here; map rotation and intensity are uniforms.
 */
import { buildEnvironmentDistribution, type EnvironmentDistribution } from '../../scene/envmap';
import type { SceneAssets } from '../../scene/assets';
import { transformMesh } from '../../scene/mesh';
import type { EnvironmentImage, Scene, TriangleMesh } from '../../scene/types';
import { buildAliasTable } from '../aliasTable';
import { BVH_TEXTURE_WIDTH, buildBvh, packBvh, type BvhMeshInput, type PackedBvh } from '../bvh';
import { BvhTextures, uploadFloatTexture } from '../bvhTextures';
import type { MeshEmitterSlots } from '../packScene';
import { EnvironmentTextures } from '../environmentTextures';
import type { Program } from '../gl/program';

/** Texture units (0 holds the running sums, 1 the scene data). */
const ENVIRONMENT_UNITS = { map: 2, marginal: 3, conditional: 4 };
const BVH_UNIT = 5;
const EMISSIVE_UNIT = 7;

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

/** What the meshes' world-space triangles depend on besides the decoded data: their transforms. */
function transformsKey(scene: Scene): string {
  return JSON.stringify(scene.meshes.map((m) => [m.position, m.rotation, m.scale]));
}

/** The world-space triangles the BVH is built over. */
export function bvhInputs(scene: Scene, assets: SceneAssets, materials: readonly number[]): BvhMeshInput[] {
  return scene.meshes.map((mesh, i) => ({ ...transformMesh(assets.meshes.get(mesh.file)!, mesh), material: materials[i] }));
}

/**
 * A BVH built ahead (by the page, in a worker: buildBvhAsync over
 * bvhInputs) for exactly these meshes: the next setMeshes for them takes it
 * instead of building on the calling thread. Only the latest is kept.
 */
let prebuilt: { key: string; data: TriangleMesh[]; packed: PackedBvh } | null = null;

export function offerBvh(scene: Scene, assets: SceneAssets, materials: readonly number[], packed: PackedBvh): void {
  prebuilt = { key: transformsKey(scene) + JSON.stringify(materials), data: scene.meshes.map((m) => assets.meshes.get(m.file)!), packed };
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
  private world: (WorldMeshes & { key: string; data: TriangleMesh[] }) | null = null;
  private bvh: { world: WorldMeshes; key: string; textures: BvhTextures; emissive: EmissiveTriangles | null } | null = null;

  constructor(private readonly gl: WebGL2RenderingContext) {}

  /** Uploads `image` (and its distribution) unless it is the one already uploaded; null frees it. */
  setEnvironmentMap(image: EnvironmentImage | null): void {
    if (this.environment?.image === image) return;
    this.environment?.textures.dispose();
    this.environment = image ? { image, textures: new EnvironmentTextures(this.gl, image, environmentDistribution(image)) } : null;
  }

  /**
   * The scene's meshes in world space and their sizes (area, triangles),
   * recomputed only when a file or a transform changes.
   */
  worldMeshes(scene: Scene, assets: SceneAssets): WorldMeshes {
    const data = scene.meshes.map((mesh) => assets.meshes.get(mesh.file)!);
    const key = transformsKey(scene);
    const w = this.world;
    if (w && w.key === key && w.data.length === data.length && w.data.every((d, i) => d === data[i])) return w;
    const meshes = scene.meshes.map((mesh, i) => transformMesh(data[i], mesh));
    this.world = { key, data, meshes, sizes: meshes.map((m) => ({ area: meshArea(m), triangles: m.indices.length / 3 })) };
    return this.world;
  }

  /**
   * Builds and uploads the BVH of `world` (each mesh's triangles carry
   * `materials[i]`) and the emissive-triangle table of `emitters`, unless
   * nothing they depend on changed.
   */
  setMeshes(world: WorldMeshes, materials: readonly number[], emitters: readonly MeshEmitterSlots[]): void {
    const key = JSON.stringify([materials, emitters]);
    if (this.bvh && this.bvh.world === world && this.bvh.key === key) return;
    this.bvh?.textures.dispose();
    this.bvh?.emissive?.dispose();
    this.bvh = null;
    if (world.meshes.length === 0) return;
    const w = this.world;
    let packed = w === world ? takePrebuilt(w.key + JSON.stringify(materials), w.data) : null;
    if (!packed) {
      const inputs = world.meshes.map((mesh, i) => ({ ...mesh, material: materials[i] }));
      packed = packBvh(buildBvh(inputs), inputs);
    }
    const emissive = emitters.length > 0 ? new EmissiveTriangles(this.gl, world, packed.triangleOrder, emitters) : null;
    this.bvh = { world, key, textures: new BvhTextures(this.gl, packed), emissive };
  }

  /** Sets the uniforms of the uploaded data on `program` (in use). */
  setUniforms(program: Program, scene: Scene): void {
    const e = scene.environment;
    if (this.environment && e && 'map' in e) this.environment.textures.setUniforms(program, ENVIRONMENT_UNITS, e.rotation, e.intensity);
  }

  /** Binds the textures to their units for `program` (in use); leaves another unit than 0 active. */
  bind(program: Program): void {
    this.environment?.textures.bind(ENVIRONMENT_UNITS);
    this.bvh?.textures.bind(program, BVH_UNIT);
    this.bvh?.emissive?.bind(program, EMISSIVE_UNIT);
  }

  dispose(): void {
    this.setEnvironmentMap(null);
    this.bvh?.textures.dispose();
    this.bvh?.emissive?.dispose();
    this.bvh = null;
  }
}

export interface WorldMeshes {
  meshes: TriangleMesh[];
  sizes: { area: number; triangles: number }[];
}

function triangleArea(p: Float32Array, i: Uint32Array, t: number): number {
  const [a, b, c] = [i[3 * t] * 3, i[3 * t + 1] * 3, i[3 * t + 2] * 3];
  const e1 = [p[b] - p[a], p[b + 1] - p[a + 1], p[b + 2] - p[a + 2]];
  const e2 = [p[c] - p[a], p[c + 1] - p[a + 1], p[c + 2] - p[a + 2]];
  return 0.5 * Math.hypot(e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]);
}

function meshArea(mesh: TriangleMesh): number {
  let area = 0;
  for (let t = 0; t < mesh.indices.length / 3; t++) area += triangleArea(mesh.positions, mesh.indices, t);
  return area;
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
    const firstInput: number[] = [];
    world.sizes.reduce((sum, size, i) => ((firstInput[i] = sum), sum + size.triangles), 0);
    const slots = emitters.reduce((n, e) => Math.max(n, e.first + e.count), 0);
    const width = BVH_TEXTURE_WIDTH;
    const data = new Float32Array(width * Math.max(1, Math.ceil(slots / width)) * 4);
    for (const e of emitters) {
      const mesh = world.meshes[e.mesh];
      const areas = Array.from({ length: e.count }, (_, t) => triangleArea(mesh.positions, mesh.indices, t));
      const table = buildAliasTable(areas);
      for (let k = 0; k < e.count; k++) {
        const o = (e.first + k) * 4;
        data[o] = bvhIndex[firstInput[e.mesh] + k];
        data[o + 1] = table.threshold[k];
        data[o + 2] = bvhIndex[firstInput[e.mesh] + table.alias[k]];
      }
    }
    this.texture = uploadFloatTexture(gl, { data, width, height: data.length / 4 / width });
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
