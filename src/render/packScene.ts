/**
 * Scene -> the packed arrays the shaders read (layout: layout/scene.ts).
 * Pure: no GL, so it is unit-tested directly.
 *
 * Each sphere light becomes a sphere with an emitter-only material; every
 * sphere whose material emits is also an emitter. Lights of the planar
 * kinds go into the planar-light table (with emitter-only materials), the
 * delta kinds into the emitter table only (src/lights/registry.ts). Light
 * sampling picks an emitter through the alias tables of lightChoice.ts: by
 * where the shading point is, or, outside their grid, by power.
 */
import { materialFeatures, materialOpacityFactor, materialSeeThrough, materialTextures, textureSlotFeatures, packEmitterOnly, packMaterial, type MaterialTexture } from '../materials/registry';
import { CHANNELS, type TextureInput } from '../scene/texture/texture';
import { ATLAS_FORMATS, type AtlasFormat, type Placement } from './textures/atlas';
import {
  type Light, lightArea, lightKindOf, lightEmitted, lightExtent, lightFeatures, lightPower, lightReach, lightSphere, packEmitter, packLightEmitter, packPlanarLight, planarBound,
} from '../lights/registry';
import type { LightReach } from '../lights/kind';
import { sphereReach } from '../lights/math';
import { buildLightChoice, type Box, type LightChoice } from './lightChoice';
import type { Material, Vec3 } from '../scene/types';
import { asRenderScene, type RenderScene as Scene } from '../scene/fileMaterials';
import type { Scene as SceneModel } from '../scene/types';
import type { MeshGroups } from './bvh/groups';
import { selectCausticGuides, type GuideSphere } from './causticGuides';
import {
  BLOCK_VEC4S, DATA_TEXELS, EMITTER, EMITTER_KINDS, GUIDE_FIELDS, GUIDE_VEC4S, HEADER, MATERIAL, MAX_TEXTURES, MESH, PLANAR_GROUP_SIZE, PLANAR_LIGHT, SECTIONS, SPHERE, TEXTURE,
} from './layout/scene';
import { planarGroupBounds, planarGroupOrder } from './planarGroups';
import { packRecord } from './layout/records';

/** Which optional shader code a scene needs (one program per combination). */
export interface SceneFeatures {
  /** Caustic guides compiled in (0..MAX_GUIDES). */
  guides: number;
  /** The material kinds whose code is compiled in, besides the default (src/materials/registry.ts). */
  materials: readonly string[];
  /** The light kinds whose code is compiled in, besides the sphere (src/lights/registry.ts). */
  lights: readonly string[];
  environmentMap: boolean;
  /** Triangle meshes (the BVH traversal). */
  meshes: boolean;
  /** Emissive meshes (light sampling of their triangles). */
  emissiveMeshes: boolean;
  /** Files named by several meshes, stored once and instanced (src/render/bvh/groups.ts). */
  instances: boolean;
  /** The atlas formats the scene's textures use (textures/texture.glsl compiles a sampler for each). */
  textureFormats: readonly AtlasFormat[];
  /** Materials that let light through (opacity below 1 or an opacity texture): the pass-through code. */
  seeThrough: boolean;
  /** Normal maps (the tangent frame and Mitsuba's normalmap adapter). */
  normalMaps: boolean;
  /** The texture slots some material uses (registry's textureSlotDefine names): only those are compiled. */
  textureSlots: readonly string[];
  /** Meshes whose material multiplies its base color by the vertex colors (glTF COLOR_0, fileMaterials.ts): their interpolation at a hit. */
  vertexColors: boolean;
}

/** A scene with nothing optional: spheres of the default material under a constant sky. */
export const BASE_FEATURES: SceneFeatures = {
  guides: 0,
  materials: [],
  lights: [],
  environmentMap: false,
  meshes: false,
  emissiveMeshes: false,
  instances: false,
  textureFormats: [],
  seeThrough: false,
  normalMaps: false,
  textureSlots: [],
  vertexColors: false,
};

/** What packing needs to know of the scene's decoded files. */
export interface PackOptions {
  /** The integral of the environment map's luminance over the sphere (its distribution's), when the scene has one. */
  environmentIntegral?: number;
  /** World-space surface area, triangle count and bounding box of each of scene.meshes (decoded and transformed). */
  meshes?: readonly { area: number; triangles: number; box?: Box }[];
  /** How the meshes are stored (src/render/bvh/groups.ts), as the BVH was built: instances need their shader code. */
  groups?: MeshGroups;
  /** Textured emissions: each emissive mesh's area-weighted mean of its texture's luminance (records.ts areaMean), by mesh index. */
  emissionScale?: ReadonlyMap<number, number>;
  /** Where a texture's image is in the atlas (src/render/textures/atlas.ts), for the inputs it feeds. */
  placement?: (image: string, input: TextureInput) => Placement;
}

/** The emissive-triangle slots of an emissive mesh (see layout/scene.ts EMITTER). */
export interface MeshEmitterSlots {
  mesh: number;
  first: number;
  count: number;
}

export interface PackedScene {
  /** The data texture: DATA_TEXELS RGBA32F texels (DATA_ROWS rows of SCENE_ROW_TEXELS). */
  data: Float32Array;
  /** The uniform block: BLOCK_VEC4S vec4s. */
  block: Float32Array;
  features: SceneFeatures;
  /** The material-table index of each of scene.meshes (its mesh record's materialBase). */
  meshMaterials: number[];
  /** The emissive meshes' triangle slots, in slot order. */
  meshEmitters: MeshEmitterSlots[];
  /** The emitter-choice tables (the texture lights/lights.glsl reads as uLightChoice). */
  lightChoice: LightChoice;
}

interface SceneSphere extends GuideSphere {
  material: Material | 'emitterOnly';
  radiance: Vec3;
}

/**
 * The weights of the emitter choice: each emitter's power, and in a scene
 * with a Dirac delta light (point, spot, directional) half power, half
 * uniform (Hesterberg's defensive mixture). A delta light is found by
 * next-event estimation alone, so a weak one picked rarely has no
 * BSDF-sampled path to make up for it: its glints and caustics through a
 * glossy surface come out as fireflies divided by its small probability
 * (lights.json's spot, pbrt-v4's power estimate over its cone: picked with
 * 0.066). The mixture keeps every probability at least half the uniform
 * one; at 64 spp it halved lights.json's median relMSE (0.148 to 0.077,
 * uniform 0.089) and its worst of five seeds (3.97 to 0.92). Scenes without
 * delta lights keep the choice by power (and version 1 and 2 their bits).
 */
export function emitterChoiceWeights(powers: readonly number[], hasDeltaLight: boolean): number[] {
  const total = powers.reduce((sum, p) => sum + p, 0);
  if (!hasDeltaLight || total <= 0) return [...powers];
  return powers.map((p) => 0.5 * (p / total) + 0.5 / powers.length);
}

export function packScene(sceneIn: Scene | SceneModel, options: PackOptions = {}): PackedScene {
  const scene = asRenderScene(sceneIn, 'packScene');
  const data = new Float32Array(DATA_TEXELS * 4);
  const block = new Float32Array(BLOCK_VEC4S * 4);
  const materials: Float32Array[] = [];
  const addMaterial = (record: Float32Array) => materials.push(record) - 1;
  const textures = new TextureTable(data, options.placement);
  const textureIndex = (t: MaterialTexture) => textures.index(t);

  const spheres = sceneSpheres(scene);
  const emitters = spheres.flatMap((s, index) => (power(s) > 0 ? [{ index, sphere: s }] : []));
  const bounds = { radius: sceneRadius(scene, spheres) };
  const environmentPower = mapEnvironmentPower(scene, bounds.radius, options.environmentIntegral);
  const meshEmitters = emissiveMeshes(scene, options.meshes ?? [], options.emissionScale);
  // The other lights' emitters come last, so scenes without them keep version 2's tables.
  // In groups of neighbours (render/planarGroups.ts): the order of the planar-light table.
  const unorderedPlanar = scene.lights.filter((l) => lightArea(l) !== null);
  const unorderedBounds = unorderedPlanar.map(planarBound);
  const planarOrder = planarGroupOrder(unorderedBounds, PLANAR_GROUP_SIZE);
  const planarLights = planarOrder.map((i) => unorderedPlanar[i]);
  const planarBounds = planarOrder.map((i) => unorderedBounds[i]);
  const otherLights = scene.lights.filter((l) => lightSphere(l) === null).flatMap((light) => {
    const p = lightPower(light, bounds);
    return p > 0 ? [{ light, power: p }] : [];
  });
  const powers = [
    ...emitters.map((e) => power(e.sphere)),
    ...(environmentPower > 0 ? [environmentPower] : []),
    ...meshEmitters.map((m) => m.power),
    ...otherLights.map((l) => l.power),
  ];
  const hasDeltaLight = otherLights.some(({ light }) => lightKindOf(light).delta);
  // Emitter slots: emissive spheres, the map, emissive meshes, the other lights.
  const environmentSlot = environmentPower > 0 ? emitters.length : -1;
  const firstMesh = emitters.length + (environmentPower > 0 ? 1 : 0);
  const firstLight = firstMesh + meshEmitters.length;
  const reaches: LightReach[] = [
    ...emitters.map(({ sphere }) => sphereReach(sphere.center, sphere.radius, sphere.radiance)),
    ...(environmentPower > 0 ? [environmentReach(scene, options.environmentIntegral ?? 0)] : []),
    ...meshEmitters.map((m) => meshReach(m, options.meshes?.[m.mesh]?.box)),
    ...otherLights.map(({ light }) => lightReach(light)),
  ];
  const lightChoice = buildLightChoice(reaches, emitterChoiceWeights(powers, hasDeltaLight), choiceBox(scene, spheres, options.meshes ?? []));
  const sphereEmitter = new Map(emitters.map((e, i) => [e.index, i]));

  spheres.forEach((sphere, i) => {
    const material = addMaterial(sphere.material === 'emitterOnly' ? packEmitterOnly(sphere.radiance) : packMaterial(sphere.material, false));
    data.set([...sphere.center, sphere.radius], (SECTIONS.sphereGeometry + i) * 4);
    data.set(packRecord(SPHERE, { material, emitter: sphereEmitter.get(i) ?? -1 }), (SECTIONS.spheres + i * SPHERE.texels) * 4);
  });
  const setEmitter = (slot: number, record: Float32Array) => data.set(record, (SECTIONS.emitters + slot * EMITTER.texels) * 4);
  emitters.forEach(({ index, sphere }, i) => {
    setEmitter(i, packEmitter({ radiance: sphere.radiance, kind: EMITTER_KINDS.sphere, primitive: index }, 'sphere', { center: sphere.center, radius: sphere.radius }));
  });
  if (environmentPower > 0) setEmitter(environmentSlot, packEmitter({ kind: EMITTER_KINDS.environment, primitive: -1 }));
  meshEmitters.forEach((m, i) => {
    setEmitter(firstMesh + i, packEmitter({ radiance: m.radiance, kind: EMITTER_KINDS.mesh, primitive: m.mesh, first: m.first, count: m.count }));
  });
  const lightSlots = new Map<Light, number>(otherLights.map(({ light }, i) => [light, firstLight + i]));
  otherLights.forEach(({ light }, i) => setEmitter(firstLight + i, packLightEmitter(light, planarLights.indexOf(light))));
  planarLights.forEach((light, i) => {
    const material = addMaterial(packEmitterOnly(lightEmitted(light)));
    data.set(packPlanarLight(light, material, lightSlots.get(light) ?? -1), (SECTIONS.planarLights + i * PLANAR_LIGHT.texels) * 4);
    data.set(planarBounds[i], (SECTIONS.planarBounds + i) * 4);
  });
  planarGroupBounds(planarBounds, PLANAR_GROUP_SIZE).forEach((sphere, g) => data.set(sphere, (SECTIONS.planarGroups + g) * 4));
  const groundMaterial = scene.ground ? addMaterial(packMaterial(scene.ground.material, false, textureIndex)) : 0;
  const meshMaterials = scene.meshes.map((mesh) => addMaterial(packMaterial(mesh.material, true, textureIndex)));
  materials.forEach((record, i) => data.set(record, (SECTIONS.materials + i * MATERIAL.texels) * 4));

  const meshSlots = new Map(meshEmitters.map((m, i) => [m.mesh, { emitter: firstMesh + i, inverseArea: 1 / m.area }]));
  meshMaterials.forEach((materialBase, i) => {
    const slot = meshSlots.get(i) ?? { emitter: -1, inverseArea: 0 };
    data.set(packRecord(MESH, { ...slot, materialBase }), (SECTIONS.meshes + i * MESH.texels) * 4);
  });

  const guides = selectCausticGuides(spheres);
  const environment = scene.environment;
  const header = packRecord(HEADER, {
    sphereCount: spheres.length,
    emitterCount: powers.length,
    groundEnabled: scene.ground ? 1 : 0,
    guideCount: guides.length,
    groundHeight: scene.ground?.height ?? 0,
    groundMaterial,
    planarLightCount: planarLights.length,
    environment: environment && 'color' in environment ? scale(environment.color, environment.intensity) : [0, 0, 0],
    environmentEmitter: environmentSlot,
    lightChoiceOrigin: lightChoice.origin,
    lightChoiceScale: lightChoice.inverseCellSize,
    lightChoiceCells: lightChoice.cells,
    lightChoiceGlobal: lightChoice.tables - 1,
  });
  block.set(header, 0);
  // The guides' geometry itself, not indices: the shader reads it with
  // constant indices, which SwiftShader does without a texture fetch.
  guides.forEach(([mirror, light], i) => {
    const base = (HEADER.texels + i * GUIDE_VEC4S) * 4;
    block.set([...spheres[mirror].center, spheres[mirror].radius], base + GUIDE_FIELDS.MIRROR * 4);
    block.set([...spheres[light].center, spheres[light].radius], base + GUIDE_FIELDS.LIGHT * 4);
  });
  const sceneMaterials = [...scene.spheres, ...scene.meshes, ...(scene.ground ? [scene.ground] : [])].map((o) => o.material);
  const kinds = materialFeatures(sceneMaterials);
  const environmentMap = environment !== null && 'map' in environment;
  const features = {
    guides: guides.length,
    materials: kinds,
    lights: lightFeatures(scene.lights),
    environmentMap,
    meshes: scene.meshes.length > 0,
    emissiveMeshes: meshEmitters.length > 0,
    instances: (options.groups?.shared.length ?? 0) > 0,
    textureFormats: ATLAS_FORMATS.filter((f) => textures.formats.has(f)),
    seeThrough: sceneMaterials.some(materialSeeThrough),
    normalMaps: sceneMaterials.some((m) => materialTextures(m).some((t) => t.input === 'normal')),
    textureSlots: textureSlotFeatures(sceneMaterials),
    vertexColors: scene.meshes.some((m) => m.vertexColors === true),
  };
  return { data, block, features, meshMaterials, meshEmitters: meshEmitters.map(({ mesh, first, count }) => ({ mesh, first, count })), lightChoice };
}

/** The environment map's reach: the same everywhere, about a quarter of its radiance's integral over the sphere (pi L for a uniform L). */
function environmentReach(scene: Scene, integral: number): LightReach {
  const intensity = scene.environment && 'map' in scene.environment ? scene.environment.intensity : 0;
  return { bound: null, strength: (integral * intensity) / 4 };
}

/** An emissive mesh's reach: its box's sphere, about half of L area / d^2 (its triangles face many ways); no box: the same everywhere. */
function meshReach(m: { radiance: Vec3; area: number; power: number }, box: Box | undefined): LightReach {
  const strength = (0.5 * m.power) / Math.PI;
  if (!box) return { bound: null, strength };
  const center: Vec3 = [0, 1, 2].map((k) => (box.min[k] + box.max[k]) / 2) as Vec3;
  return { bound: { center, radius: Math.hypot(box.max[0] - box.min[0], box.max[1] - box.min[1], box.max[2] - box.min[2]) / 2 }, strength };
}

/**
 * The box the emitter-choice grid covers: the scene's objects, finite
 * lights, camera and the ground's height, padded by 2% of its diagonal.
 * Shading points outside it use the global table.
 */
function choiceBox(scene: Scene, spheres: readonly SceneSphere[], meshes: readonly { box?: Box }[]): Box | null {
  const min: Vec3 = [Infinity, Infinity, Infinity];
  const max: Vec3 = [-Infinity, -Infinity, -Infinity];
  const add = (p: Vec3, r = 0) => {
    for (let k = 0; k < 3; k++) {
      min[k] = Math.min(min[k], p[k] - r);
      max[k] = Math.max(max[k], p[k] + r);
    }
  };
  add(scene.camera.position);
  spheres.forEach((s) => add(s.center, s.radius));
  scene.lights.forEach((l) => {
    const extent = lightExtent(l);
    if (extent) add(extent.center, extent.radius);
  });
  meshes.forEach((m) => {
    if (m.box) {
      add(m.box.min);
      add(m.box.max);
    }
  });
  if (scene.ground) add([min[0], scene.ground.height, min[2]]);
  if (!min.every(Number.isFinite) || !max.every(Number.isFinite)) return null;
  const pad = 0.02 * Math.hypot(max[0] - min[0], max[1] - min[1], max[2] - min[2]) + 1e-3;
  return { min: min.map((v) => v - pad) as Vec3, max: max.map((v) => v + pad) as Vec3 };
}

/** The scene's spheres in shader order: `spheres`, then the sphere lights as emitter-only spheres. */
function sceneSpheres(scene: Scene): SceneSphere[] {
  return [
    ...scene.spheres.map((s) => ({ center: s.center, radius: s.radius, material: s.material, radiance: emittedRadiance(s.material) })),
    ...scene.lights.flatMap((l) => {
      const sphere = lightSphere(l);
      return sphere ? [{ ...sphere, material: 'emitterOnly' as const, radiance: lightEmitted(l) }] : [];
    }),
  ];
}

/**
 * The radiance light sampling sees from a material: its emission where it
 * is opaque, so times its opacity (the format's o * Le; a hit sees it with
 * probability o). The material record keeps the emission itself.
 */
function emittedRadiance(m: Material): Vec3 {
  return m.emission ? scale(m.emission.color, m.emission.intensity * materialOpacityFactor(m)) : [0, 0, 0];
}

/** Emitted power of a sphere: pi * 4 pi r^2 * luminance of its radiance. */
function power(s: SceneSphere): number {
  return 4 * Math.PI * Math.PI * s.radius * s.radius * luminance(s.radiance);
}

/**
 * Power of the environment map as pbrt-v4 estimates an infinite light's:
 * pi R^2 times its luminance integrated over the sphere, R the scene's
 * radius (sceneRadius). 0 when the scene has no map or a black one.
 */
function mapEnvironmentPower(scene: Scene, radius: number, integral = 0): number {
  const environment = scene.environment;
  if (!environment || !('map' in environment) || !(integral > 0) || !(environment.intensity > 0)) return 0;
  return Math.PI * radius * radius * integral * environment.intensity;
}

/**
 * The radius of a sphere around the scene's objects and camera (at least
 * 1), about their mean position: what an infinite light's power is
 * measured over (the environment map's, and a light's at infinity).
 */
function sceneRadius(scene: Scene, spheres: readonly SceneSphere[]): number {
  const others = scene.lights.filter((l) => lightSphere(l) === null).flatMap((l) => lightExtent(l) ?? []);
  const points = [scene.camera.position, ...spheres.map((s) => s.center), ...scene.meshes.map((m) => m.position), ...others.map((o) => o.center)];
  const center = [0, 1, 2].map((k) => points.reduce((sum, p) => sum + p[k], 0) / points.length);
  const away = (p: Vec3) => Math.hypot(p[0] - center[0], p[1] - center[1], p[2] - center[2]);
  let radius = 1;
  for (const p of points) radius = Math.max(radius, away(p));
  for (const s of [...spheres, ...others]) radius = Math.max(radius, away(s.center) + s.radius);
  return radius;
}

const luminance = (c: Vec3) => 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];

/**
 * Meshes whose material emits, with their power (pi * area * luminance: one
 * side emits) and their triangles' slots in the emissive-triangle texture.
 */
function emissiveMeshes(scene: Scene, sizes: readonly { area: number; triangles: number }[], emissionScale?: ReadonlyMap<number, number>) {
  let first = 0;
  return scene.meshes.flatMap((mesh, i) => {
    const radiance = emittedRadiance(mesh.material);
    const size = sizes[i];
    const textured = mesh.material.emission?.texture ? (emissionScale?.get(i) ?? 1) : 1;
    const power = size ? Math.PI * size.area * luminance(radiance) * textured : 0;
    if (!(power > 0)) return [];
    const slots = { mesh: i, first, count: size.triangles, area: size.area, power, radiance };
    first += size.triangles;
    return [slots];
  });
}

const scale = (v: Vec3, s: number): Vec3 => [v[0] * s, v[1] * s, v[2] * s];

/**
 * The texture table (layout/scene.ts TEXTURE): one record per distinct
 * texture and input, written as materials ask for their index. Exported for
 * the texture-lookup kernel (src/headless/textureKernels.ts), which packs
 * its textures with it.
 */
export class TextureTable {
  private readonly indices = new Map<string, number>();
  readonly formats = new Set<AtlasFormat>();

  constructor(
    private readonly data: Float32Array,
    private readonly placement?: (image: string, input: TextureInput) => Placement,
  ) {}

  index({ texture: t, input }: Pick<MaterialTexture, 'texture' | 'input'>): number {
    const key = JSON.stringify([t, input]);
    const known = this.indices.get(key);
    if (known !== undefined) return known;
    if (!this.placement) throw new Error(`packScene: ${t.image} is not placed (pass options.placement)`);
    const i = this.indices.size;
    if (i >= MAX_TEXTURES) throw new Error(`a scene reads at most ${MAX_TEXTURES} distinct textures`);
    const p = this.placement(t.image, input);
    this.formats.add(p.format);
    const r = (t.uv.rotation * Math.PI) / 180;
    const [sx, sy] = t.uv.scale;
    const [ox, oy] = t.uv.offset;
    const record = packRecord(TEXTURE, {
      placement: [ATLAS_FORMATS.indexOf(p.format), p.layer, p.x, p.y],
      size: [p.width, p.height, input === 'scalar' ? CHANNELS.indexOf(t.channel) : -1, t.cutoff ?? -1],
      uRow: [Math.cos(r) * sx, Math.sin(r) * sy, ox, input === 'normal' ? (t.scale as number) : 0],
      vRow: [-Math.sin(r) * sx, Math.cos(r) * sy, oy, 0],
    });
    this.data.set(record, (SECTIONS.textures + i * TEXTURE.texels) * 4);
    this.indices.set(key, i);
    return i;
  }
}
