/**
 * Which GLSL chunks make up each program, in dependency order, and the
 * defines they are compiled with. Names are paths under src/shaders/;
 * `generated/` chunks are made here from the packed layout and the material
 * registry; the material kinds' chunks are named relative to src/shaders/. No shader text
 * is imported here, so Node tools (bench/shader-ab.ts) can assemble the same
 * programs from files; the page gets the text through shaderSources.ts.
 */
import { DELTA_ALPHA, GUIDE_MARGIN, GUIDE_PROBABILITY } from './causticGuides';
import type { ShaderChunk } from './gl/shaderSource';
import { sceneLayoutDefines, sceneLayoutGlsl } from './layout/scene';
import type { SceneFeatures } from './packScene';
import { samplingDefines, type SamplerKind } from './sampling';
import { bvhDefines } from './bvhTextures';
import { ATLAS_FORMATS } from './textures/atlas';
import { bsdfDispatchGlsl, surfaceInputsGlsl, textureSlotDefines, MATERIAL_CHUNK_GUARDS, MATERIAL_CHUNK_NAMES, materialDefines, materialFeatureDefines, materialGlsl } from '../materials/registry';
import { emitterGlsl, LIGHT_CHUNK_GUARDS, LIGHT_CHUNK_NAMES, lightDispatchGlsl, lightFeatureDefines } from '../lights/registry';

/** The chunks every kernel that touches the scene needs. */
export const SCENE_CHUNK_NAMES = [
  'common/math.glsl',
  'common/rng.glsl',
  'common/sampling.glsl',
  'scene/layout.glsl',
  'generated/records.glsl',
  'generated/materials.glsl',
  'generated/emitters.glsl',
  'scene/access.glsl',
  'scene/bvh.glsl',
  'scene/instances.glsl',
  'scene/intersect.glsl',
  'textures/texture.glsl',
  'generated/surface_inputs.glsl',
  'surface.glsl',
  'bsdf/ggx.glsl',
  'bsdf/fresnel.glsl',
  ...MATERIAL_CHUNK_NAMES,
  'generated/bsdf_dispatch.glsl',
  'bsdf/bsdf.glsl',
  'lights/light_sample.glsl',
  'lights/planar.glsl',
  ...LIGHT_CHUNK_NAMES,
  'lights/environment_map.glsl',
  'lights/mesh_emitter.glsl',
  'generated/light_dispatch.glsl',
  'lights/lights.glsl',
  'lights/caustic_guide.glsl',
];
export const TRACE_CHUNK_NAMES = [...SCENE_CHUNK_NAMES, 'camera.glsl', 'integrator.glsl', 'trace.frag'];

const GENERATED: Record<string, () => string> = {
  'generated/records.glsl': sceneLayoutGlsl,
  'generated/materials.glsl': materialGlsl,
  'generated/bsdf_dispatch.glsl': bsdfDispatchGlsl,
  'generated/emitters.glsl': emitterGlsl,
  'generated/light_dispatch.glsl': lightDispatchGlsl,
  'generated/surface_inputs.glsl': () => `#if HAS_SURFACE_INPUTS\n${surfaceInputsGlsl()}\n#endif`,
};

/**
 * The named chunks, generated ones made here and the rest read through
 * `source`; a material kind's chunk is compiled only in programs with its
 * HAS_<KIND> (SwiftShader's compile time grows with the source).
 */
export function assembleChunks(names: readonly string[], source: (name: string) => string): ShaderChunk[] {
  return names.map((name) => {
    const generated = GENERATED[name];
    if (generated) return { name, source: generated() };
    const guard = MATERIAL_CHUNK_GUARDS.get(name) ?? LIGHT_CHUNK_GUARDS.get(name);
    return guard ? { name, source: `#if ${guard}\n${source(name)}\n#endif`, lineOffset: 1 } : { name, source: source(name) };
  });
}

/** Defines of the scene chunks, before the per-variant feature switches. */
export function sceneDefines(sampler: SamplerKind = 'kronecker', russianRoulette = false): Record<string, string | number> {
  return {
    ...sceneLayoutDefines(),
    ...materialDefines(),
    ...samplingDefines(sampler, russianRoulette),
    GUIDE_PROBABILITY: GUIDE_PROBABILITY.toFixed(6),
    GUIDE_MARGIN: GUIDE_MARGIN.toFixed(6),
    DELTA_ALPHA: DELTA_ALPHA.toExponential(),
    ...bvhDefines(),
  };
}

/** Whether the program reads the materials' surface inputs (textures, opacity). */
const surfaceInputs = (f: SceneFeatures) => f.textureFormats.length > 0 || f.seeThrough;

/** The feature switches of one program variant. */
export function featureDefines(features: SceneFeatures): Record<string, number> {
  return {
    CAUSTIC_GUIDES: features.guides,
    ...materialFeatureDefines(features.materials, surfaceInputs(features)),
    ...lightFeatureDefines(features.lights),
    HAS_SURFACE_INPUTS: surfaceInputs(features) ? 1 : 0,
    HAS_TEXTURES: features.textureFormats.length > 0 ? 1 : 0,
    ...Object.fromEntries(ATLAS_FORMATS.map((f) => [`HAS_TEXTURES_${f.toUpperCase()}`, features.textureFormats.includes(f) ? 1 : 0])),
    HAS_SEE_THROUGH: features.seeThrough ? 1 : 0,
    HAS_NORMAL_MAPS: features.normalMaps ? 1 : 0,
    ...textureSlotDefines(features.textureSlots),
    HAS_TEXTURED_EMISSION: features.textureSlots.some((s) => s.endsWith('_EMISSION')) && features.emissiveMeshes ? 1 : 0,
    HAS_ENV_MAP: features.environmentMap ? 1 : 0,
    HAS_MESHES: features.meshes ? 1 : 0,
    HAS_EMISSIVE_MESHES: features.emissiveMeshes ? 1 : 0,
    HAS_INSTANCES: features.instances ? 1 : 0,
    HAS_VERTEX_COLORS: features.vertexColors && features.meshes ? 1 : 0,
  };
}
