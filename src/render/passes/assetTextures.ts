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
import { buildBvh, packBvh, type BvhMeshInput, type PackedBvh } from '../bvh';
import { BvhTextures } from '../bvhTextures';
import { EnvironmentTextures } from '../environmentTextures';
import type { Program } from '../gl/program';

/** Texture units (0 holds the running sums, 1 the scene data). */
const ENVIRONMENT_UNITS = { map: 2, marginal: 3, conditional: 4 };
const BVH_UNITS = { nodes: 5, triangles: 6 };

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

/** What the BVH of a scene's meshes depends on besides the decoded data: transforms and material slots. */
function meshesKey(scene: Scene, materials: readonly number[]): string {
  return JSON.stringify(scene.meshes.map((m, i) => [m.position, m.rotation, m.scale, materials[i]]));
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
  prebuilt = { key: meshesKey(scene, materials), data: scene.meshes.map((m) => assets.meshes.get(m.file)!), packed };
}

function takePrebuilt(key: string, data: TriangleMesh[]): PackedBvh | null {
  const ready = prebuilt;
  if (!ready || ready.key !== key || ready.data.length !== data.length || !ready.data.every((d, i) => d === data[i])) return null;
  prebuilt = null;
  return ready.packed;
}

export class AssetTextures {
  private environment: { image: EnvironmentImage; textures: EnvironmentTextures } | null = null;
  private bvh: { key: string; data: TriangleMesh[]; textures: BvhTextures } | null = null;

  constructor(private readonly gl: WebGL2RenderingContext) {}

  /** Uploads `image` (and its distribution) unless it is the one already uploaded; null frees it. */
  setEnvironmentMap(image: EnvironmentImage | null): void {
    if (this.environment?.image === image) return;
    this.environment?.textures.dispose();
    this.environment = image ? { image, textures: new EnvironmentTextures(this.gl, image, environmentDistribution(image)) } : null;
  }

  /**
   * Builds and uploads the BVH of the scene's meshes (each mesh's triangles
   * carry `materials[i]`) unless nothing it depends on changed.
   */
  setMeshes(scene: Scene, assets: SceneAssets, materials: readonly number[]): void {
    const data = scene.meshes.map((mesh) => assets.meshes.get(mesh.file)!);
    const key = meshesKey(scene, materials);
    if (this.bvh && this.bvh.key === key && this.bvh.data.every((d, i) => d === data[i]) && data.length === this.bvh.data.length) return;
    this.bvh?.textures.dispose();
    this.bvh = null;
    if (data.length === 0) return;
    let packed = takePrebuilt(key, data);
    if (!packed) {
      const inputs = bvhInputs(scene, assets, materials);
      packed = packBvh(buildBvh(inputs), inputs);
    }
    this.bvh = { key, data, textures: new BvhTextures(this.gl, packed) };
  }

  /** Sets the uniforms of the uploaded data on `program` (in use). */
  setUniforms(program: Program, scene: Scene): void {
    const e = scene.environment;
    if (this.environment && e && 'map' in e) this.environment.textures.setUniforms(program, ENVIRONMENT_UNITS, e.rotation, e.intensity);
  }

  /** Binds the textures to their units for `program` (in use); leaves another unit than 0 active. */
  bind(program: Program): void {
    this.environment?.textures.bind(ENVIRONMENT_UNITS);
    this.bvh?.textures.bind(program, BVH_UNITS);
  }

  dispose(): void {
    this.setEnvironmentMap(null);
    this.bvh?.textures.dispose();
    this.bvh = null;
  }
}
