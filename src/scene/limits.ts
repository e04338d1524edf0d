/**
 * Limits of the scene model. They are validated by the schema and injected
 * into the shaders as #defines (see src/render/layout/scene.ts), so they live here once.
 */
/**
 * Spheres and lights in one scene. Each has records in the scene tables
 * (src/render/layout/scene.ts: a sphere, a material, an emitter when it
 * emits), which run on over as many 2048-texel rows of the data texture as
 * they need, so these bound memory, not a texture width: with MAX_MESHES the
 * tables take about 12 000 texels, 6 rows (DATA_ROWS, 192 KB). They are not a
 * speed limit: every ray is tested against every sphere and light (there is
 * no acceleration structure for spheres), so 1024 spheres cost about 8x what
 * 128 do per bounce, which is the scene's choice to make; light sampling
 * picks from the alias table in constant time. A sphere is about 100-150
 * bytes of JSON, so a full scene stays well inside MAX_SCENE_BYTES.
 */
export const MAX_SPHERES = 1024;
export const MAX_LIGHTS = 64;
export const MAX_BOUNCES = 64;
export const MAX_IMAGE_SIZE = 8192;
/** Largest scene document accepted from a file or a link, in bytes. */
export const MAX_SCENE_BYTES = 1_000_000;
/**
 * Meshes in one scene. Each has a material, a mesh record and, when it
 * emits, an emitter in the scene tables (a few texels); their triangles share one
 * BVH bounded by MAX_TRIANGLES (src/render/bvh/pack.ts), so the count bounds
 * only the tables.
 */
export const MAX_MESHES = 256;
/**
 * Largest mesh file read, in bytes (a `.glb`, a `.gltf`'s `.bin`, an OBJ, a
 * PLY): 1 GiB. The CLI checks a file's size before reading it
 * (src/node/readMesh.ts; src/node/sceneFiles.ts applies it to every file a
 * scene names, since no valid image or map is that large: their decoded
 * limits are smaller), and a GLB's declared length is checked against it
 * before parsing (src/scene/mesh/gltf.ts), so a 2 GB model is refused with a
 * message instead of being read whole.
 */
export const MAX_MESH_FILE_BYTES = 2 ** 30;
