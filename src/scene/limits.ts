/**
 * Limits of the scene model. They are validated by the schema and injected
 * into the shaders as #defines (see src/render/layout/scene.ts), so they live here once.
 */
export const MAX_SPHERES = 128;
export const MAX_LIGHTS = 16;
export const MAX_BOUNCES = 64;
export const MAX_IMAGE_SIZE = 8192;
/** Largest scene document accepted from a file or a link, in bytes. */
export const MAX_SCENE_BYTES = 1_000_000;
/** Meshes in one scene (each has its own material record). */
export const MAX_MESHES = 64;
/** Range of a dielectric's index of refraction. */
export const MIN_IOR = 1.01;
export const MAX_IOR = 4;
