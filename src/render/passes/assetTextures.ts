/**
 * The GPU copies of a scene's decoded files, from the prepared geometry
 * (src/render/geometry/): the environment map (image and sampling
 * distribution) and the BVH over the meshes' triangles, in groups
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
import type { EnvironmentImage } from '../../scene/types';
import type { RenderScene as Scene } from '../../scene/fileMaterials';
import { BVH_TEXTURE_WIDTH, MAX_INSTANCES, buildAndPackGroups } from '../bvh';
import { emissiveTriangleRecords, instanceRecords } from '../geometry/records';
import { groupInputs, prebuiltFor, type PrebuiltBvh, type WorldMeshes } from '../geometry/world';
import { INSTANCE } from '../layout/scene';
import { BvhTextures } from '../bvhTextures';
import type { MeshEmitterSlots } from '../packScene';
import { EnvironmentTextures } from '../environmentTextures';
import { TextureAtlas } from '../textures/textureAtlas';
import { materialTextures } from '../../materials/registry';
import type { TextureImage } from '../../scene/texture/image';
import type { Program } from '../gl/program';
import { createDataTexture, uploadDataTexture } from '../gl/dataTexture';
import { ENVIRONMENT_UNITS, TEXTURE_UNITS } from '../gl/textureUnits';

/**
 * The sampling distribution of a decoded map: the one it carries (the page
 * builds it in its map worker, off the main thread: SceneAssets hands it in
 * with the image), else built here once per image (tens of milliseconds for
 * a 2k map) and kept with it.
 */
export function environmentDistribution(image: EnvironmentImage): EnvironmentDistribution {
  return (image.distribution ??= buildEnvironmentDistribution(image));
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

  readonly textures: TextureAtlas;

  constructor(private readonly gl: WebGL2RenderingContext) {
    this.textures = new TextureAtlas(gl);
  }

  /** Uploads the images the scene's materials read (unless the atlas holds exactly these). */
  setTextures(scene: Scene, images: ReadonlyMap<string, TextureImage>): void {
    const materials = [...(scene.ground ? [scene.ground.material] : []), ...scene.meshes.map((m) => m.material)];
    this.textures.set(materials.flatMap((m) => materialTextures(m).map((t) => ({ image: t.texture.image, input: t.input }))), images);
  }

  /** Uploads `image` (and its distribution) unless it is the one already uploaded; null frees it. */
  setEnvironmentMap(image: EnvironmentImage | null): void {
    if (this.environment?.image === image) return;
    this.environment?.textures.dispose();
    this.environment = image ? { image, textures: new EnvironmentTextures(this.gl, image, environmentDistribution(image)) } : null;
  }

  /**
   * Builds (or takes `prebuilt`, when built for these meshes) and uploads
   * the BVH of `world`, unless its meshes' data, grouping and copies are
   * unchanged (materials do not matter: the mesh records give them), its
   * instance table, and the emissive-triangle table of `emitters` unless
   * their slots are unchanged.
   */
  setMeshes(world: WorldMeshes, emitters: readonly MeshEmitterSlots[], prebuilt?: PrebuiltBvh, means: ReadonlyMap<number, Float32Array> = new Map()): void {
    const emissiveKey = JSON.stringify(emitters) + [...means.values()].map((m) => meansId(m)).join(',');
    const emissive = (triangleOrder: Uint32Array) => ({
      key: emissiveKey,
      table: emitters.length > 0 ? new EmissiveTriangles(this.gl, emissiveTriangleRecords(world, triangleOrder, emitters, means)) : null,
    });
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
    let packed = prebuiltFor(prebuilt, world);
    if (!packed) {
      packed = buildAndPackGroups(groupInputs(world.groups, (i) => world.meshes[i]!, (i) => world.data[i], world.vertexColors));
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
    this.textures.bind(program);
  }

  dispose(): void {
    this.setEnvironmentMap(null);
    this.textures.dispose();
    this.bvh?.textures.dispose();
    this.bvh?.emissive.table?.dispose();
    this.bvh?.instances?.dispose();
    this.bvh = null;
  }
}

/** A stable id per means array (the emissive table is rebuilt when they change). */
const MEANS_IDS = new WeakMap<Float32Array, number>();
let nextMeansId = 0;
const meansId = (m: Float32Array) => MEANS_IDS.get(m) ?? (MEANS_IDS.set(m, ++nextMeansId), nextMeansId);

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

/** The emissive triangles as a texture for lights/mesh_emitter.glsl (see emissiveTriangleRecords). */
class EmissiveTriangles {
  private readonly texture: WebGLTexture;

  /** `data`: emissiveTriangleRecords (src/render/geometry/records.ts), BVH_TEXTURE_WIDTH texels a row. */
  constructor(private readonly gl: WebGL2RenderingContext, data: Float32Array) {
    this.texture = createDataTexture(gl, BVH_TEXTURE_WIDTH, data.length / 4 / BVH_TEXTURE_WIDTH, data);
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
