/**
 * Every texture unit the renderer's programs (and the headless test
 * kernels) bind a texture to, in one place, each distinct: a program built
 * from the scene chunks sees the scene's units and its own pass's at once.
 * WebGL2 guarantees 16 units per fragment shader.
 */
export const TEXTURE_UNITS = {
  /** The running radiance sums a pass reads (trace.frag, display.frag uAccumulation). */
  accumulation: 0,
  /** The scene data texture (scene/layout.glsl uSceneData). */
  sceneData: 1,
  /** The environment map's image and its alias tables (lights/environment_map.glsl). */
  environmentMap: 2,
  environmentMarginal: 3,
  environmentConditional: 4,
  /** The packed BVH (scene/bvh.glsl uBvh). */
  bvh: 5,
  /** The rays of the BVH test kernel (test/bvh_kernels.frag uRays; headless page only). */
  kernelRays: 6,
  /** The emissive triangles' alias tables (lights/mesh_emitter.glsl uEmissiveTriangles). */
  emissiveTriangles: 7,
  /** The instance table (scene/layout.glsl uInstances). */
  instances: 8,
  /** The AOV pass's running sums (aov.frag uAlbedoSums, uNormalSums). */
  albedoSums: 9,
  normalSums: 10,
  /** The texture atlases, one array per storage format (textures/texture.glsl). */
  texturesSrgb8: 11,
  texturesLinear8: 12,
  texturesFloat: 13,
  /** The emitter-choice tables (lights/lights.glsl uLightChoice). */
  lightChoice: 14,
  /** Adaptive sampling's per-cell first sample and count (trace.frag uCellSamples). */
  cellSamples: 15,
} as const;

/** The environment map's units in the form EnvironmentTextures takes. */
export const ENVIRONMENT_UNITS = {
  map: TEXTURE_UNITS.environmentMap,
  marginal: TEXTURE_UNITS.environmentMarginal,
  conditional: TEXTURE_UNITS.environmentConditional,
} as const;
