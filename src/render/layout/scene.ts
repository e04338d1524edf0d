/**
 * The packed scene, defined once. Tables (materials, spheres, emitters) live
 * in one RGBA32F data texture read with texelFetch; per-scene constants (the
 * header and the caustic guides) live in a small uniform block read with
 * constant indices. `packScene` writes both; the shaders read them through
 * the defines and loaders generated here (`sceneLayoutDefines`,
 * `sceneLayoutGlsl`).
 */
import { MAX_LIGHTS, MAX_MESHES, MAX_SPHERES } from '../../scene/limits';
import { MATERIAL_TEXELS } from '../../materials/registry';
import { EMITTER_KINDS, emitterLayout, lightDefines, PLANAR_LIGHT } from '../../lights/registry';
import { defineRecord, recordDefines, recordGlsl, type RecordLayout } from './records';

/** Emitter kinds (Emitter.kind in GLSL): src/lights/registry.ts. */
export { EMITTER_KINDS, PLANAR_LIGHT };

/**
 * A row of the material table: its layout is the material kind's
 * (src/materials/registry.ts, which generates its GLSL); every row has the
 * largest kind's texels.
 */
export const MATERIAL = { texels: MATERIAL_TEXELS } as const;

/**
 * A sphere (also each sphere light, with an emitter-only material): its
 * material and `emitter`, its slot in the emitter table (-1 when it does
 * not emit), for the MIS weight of a hit on it (the probability of picking
 * it is read at the previous vertex: render/lightChoice.ts). Its
 * geometry (center.xyz, radius) is a texel of its own in the
 * sphere-geometry table (SECTIONS.sphereGeometry), which the intersection
 * loops read for every sphere on every ray.
 */
export const SPHERE = defineRecord('SphereRecord', [
  ['material', 'int'],
  ['emitter', 'int'],
]);

/**
 * An entry of the light-sampling table; `pdf` is the probability of picking
 * it. Its layout is its kind's (src/lights/registry.ts, which generates the
 * GLSL): a header (radiance, pdf, kind, primitive, first, count), then the
 * kind's fields; this is a sphere's (centre and radius; `primitive` the
 * sphere). Meshes: `primitive` the mesh, its emissive triangles the slots
 * `first` .. `first + count - 1` of the emissive-triangle texture
 * (lights/mesh_emitter.glsl); area lights: `primitive` the planar-light slot.
 */
export const EMITTER = emitterLayout();

/**
 * A mesh: `emitter` its slot in the emitter table (-1 when it does not
 * emit) and `inverseArea` 1 / its area (light sampling draws a point on it
 * with that density per unit area once it picked the mesh), for the MIS
 * weight of a hit; `materialBase` the material-table index of its material 0: a hit's
 * material is materialBase + the triangle's mesh-local material index
 * (src/render/bvh/pack.ts), so the BVH holds no global material slot.
 */
export const MESH = defineRecord('MeshRecord', [['emitter', 'int'], ['materialBase', 'int'], ['inverseArea', 'float']]);

/**
 * An instance of a BVH group (src/render/bvh/groups.ts), in the instance
 * table (its own small texture, scene/instances.glsl): the rows of its
 * world-to-object and object-to-world matrices (3x4: a row dotted with
 * (x, y, z, 1)), its group's root node, and the mesh its triangles take
 * (-1: each triangle's own, as in the world group); the mesh's record gives
 * the material.
 */
export const INSTANCE = defineRecord('InstanceRecord', [
  ['toObjectX', 'vec4'],
  ['toObjectY', 'vec4'],
  ['toObjectZ', 'vec4'],
  ['toWorldX', 'vec4'],
  ['toWorldY', 'vec4'],
  ['toWorldZ', 'vec4'],
  ['root', 'int'],
  ['mesh', 'int'],
]);

/** Per-scene constants (uniform block `SceneHeader`, `uHeader[]`). */
export const HEADER = defineRecord('Header', [
  ['sphereCount', 'int'],
  ['emitterCount', 'int'],
  ['groundEnabled', 'int'],
  ['guideCount', 'int'],
  ['groundHeight', 'float'],
  ['groundMaterial', 'int'],
  /** Rectangle and disk lights (the planar-light table). */
  ['planarLightCount', 'int'],
  ['environment', 'vec3'],
  /** The environment map's slot in the emitter table (-1: none, or a constant sky, which is never sampled). */
  ['environmentEmitter', 'int'],
  /**
   * The grid of emitter-choice tables (render/lightChoice.ts): its corner,
   * cells per unit length and cells per axis (0: no grid), and the index of
   * the global table (points outside the grid).
   */
  ['lightChoiceOrigin', 'vec3'],
  ['lightChoiceGlobal', 'int'],
  ['lightChoiceScale', 'vec3'],
  ['lightChoiceCells', 'vec3'],
]);

/** caustic_guide.glsl holds exactly two named cones: change both together. */
export const MAX_GUIDES = 2;
/** vec4 slots of one guide: the mirror's and the light's [center.xyz, radius]. */
export const GUIDE_FIELDS = { MIRROR: 0, LIGHT: 1 } as const;
export const GUIDE_VEC4S = Object.keys(GUIDE_FIELDS).length;

/**
 * A texture a material reads (textures/texture.glsl), one per distinct
 * texture and input: where its image is (format 0 srgb8, 1 linear8, 2
 * float; the page of that format's atlas array; the corner there), its size
 * as stored, the channel a scalar reads (-1: RGB) and its cutoff (-1:
 * none), and the `uv` transform's rows (u' = dot(uRow.xyz, (u, v, 1)),
 * likewise v'), a normal map's scale in uRow.w.
 */
export const TEXTURE = defineRecord('TextureRecord', [
  ['placement', 'vec4'],
  ['size', 'vec4'],
  ['uRow', 'vec4'],
  ['vRow', 'vec4'],
]);
/** Distinct textures a scene may read. */
export const MAX_TEXTURES = 512;

/** Lights become spheres; each sphere, light, mesh and the ground has its own material. */
export const MAX_SCENE_SPHERES = MAX_SPHERES + MAX_LIGHTS;
export const MAX_MATERIALS = MAX_SCENE_SPHERES + MAX_MESHES + 1;
export const MAX_EMITTERS = MAX_SCENE_SPHERES + 1 + MAX_MESHES;

/** Width of the emitter-choice texture (render/lightChoice.ts): a power of two, so the shader splits an index with a mask and a shift. */
export const LIGHT_CHOICE_WIDTH = 2048;

/** Planar lights per culling group (render/planarGroups.ts). */
export const PLANAR_GROUP_SIZE = 4;

/** The tables of the data texture, in order, with their texels. */
const TABLES = [
  // First and within row 0: the intersection loops fetch it with a constant
  // row (a dynamic row cost the seed scene 7% of its path rate in SwiftShader).
  ['sphereGeometry', MAX_SCENE_SPHERES],
  // The planar lights' bounding spheres, which the same loops test first.
  ['planarBounds', MAX_LIGHTS],
  // Spheres around runs of PLANAR_GROUP_SIZE of them (render/planarGroups.ts).
  ['planarGroups', Math.ceil(MAX_LIGHTS / PLANAR_GROUP_SIZE)],
  ['materials', MAX_MATERIALS * MATERIAL.texels],
  ['spheres', MAX_SCENE_SPHERES * SPHERE.texels],
  ['emitters', MAX_EMITTERS * EMITTER.texels],
  ['meshes', MAX_MESHES * MESH.texels],
  ['textures', MAX_TEXTURES * TEXTURE.texels],
  ['planarLights', MAX_LIGHTS * PLANAR_LIGHT.texels],
] as const;
type Table = (typeof TABLES)[number][0];
/** First texel of each table in the data texture. */
export const SECTIONS = Object.fromEntries(
  TABLES.map(([name], i) => [name, TABLES.slice(0, i).reduce((sum, [, texels]) => sum + texels, 0)]),
) as Readonly<Record<Table, number>>;
/**
 * Width of a row of the data texture: the tables run on from one row into the
 * next (a record may straddle two rows; each texel is addressed on its own).
 * 2048 is the widest texture every WebGL2 device must support
 * (MAX_TEXTURE_SIZE >= 2048), and a power of two, so sceneData splits a texel
 * index with a mask and a shift (SCENE_ROW_BITS).
 */
export const SCENE_ROW_TEXELS = 2048;
const SCENE_ROW_BITS = Math.log2(SCENE_ROW_TEXELS);
if (!Number.isInteger(SCENE_ROW_BITS)) throw new Error('SCENE_ROW_TEXELS must be a power of two');
/** Texels the tables fill, from texel 0. */
export const TABLE_TEXELS = TABLES.reduce((sum, [, texels]) => sum + texels, 0);
if (SECTIONS.materials > SCENE_ROW_TEXELS) throw new Error('the sphere-geometry and planar-bound tables must fit in row 0');
/** Height of the data texture: the rows the tables need. */
export const DATA_ROWS = Math.ceil(TABLE_TEXELS / SCENE_ROW_TEXELS);
/** Texels of the data texture, DATA_ROWS whole rows (past TABLE_TEXELS: padding, 0). */
export const DATA_TEXELS = DATA_ROWS * SCENE_ROW_TEXELS;
/** vec4s of the uniform block: the header, then the guides. */
export const BLOCK_VEC4S = HEADER.texels + MAX_GUIDES * GUIDE_VEC4S;

export function sceneLayoutDefines(): Record<string, number> {
  return {
    ...recordDefines(SPHERE),
    ...lightDefines(),
    ...recordDefines(PLANAR_LIGHT),
    ...recordDefines(MESH),
    ...recordDefines(TEXTURE),
    ...recordDefines(INSTANCE),
    SPHERE_GEOMETRY_FIRST: SECTIONS.sphereGeometry,
    MATERIALS_FIRST: SECTIONS.materials,
    SPHERES_FIRST: SECTIONS.spheres,
    EMITTERS_FIRST: SECTIONS.emitters,
    MESHES_FIRST: SECTIONS.meshes,
    PLANAR_LIGHTS_FIRST: SECTIONS.planarLights,
    PLANAR_BOUNDS_FIRST: SECTIONS.planarBounds,
    PLANAR_GROUPS_FIRST: SECTIONS.planarGroups,
    PLANAR_GROUP_SIZE,
    LIGHT_CHOICE_WIDTH,
    LIGHT_CHOICE_WIDTH_LOG2: Math.log2(LIGHT_CHOICE_WIDTH),
    TEXTURES_FIRST: SECTIONS.textures,
    SCENE_ROW_TEXELS,
    SCENE_ROW_BITS,
    MAX_SCENE_SPHERES,
    HEADER_TEXELS: HEADER.texels,
    BLOCK_VEC4S,
    MAX_GUIDES,
    GUIDE_VEC4S,
    GUIDE_MIRROR: GUIDE_FIELDS.MIRROR,
    GUIDE_LIGHT: GUIDE_FIELDS.LIGHT,
  };
}

/** The generated GLSL: a struct and a loader per record (see records.ts). */
export function sceneLayoutGlsl(): string {
  const tables: RecordLayout[] = [SPHERE, MESH, TEXTURE];
  return [
    '// Generated from src/render/layout/scene.ts: do not edit.',
    ...tables.map((layout) => recordGlsl(layout, 'sceneData')),
    recordGlsl(HEADER, 'headerTexel'),
    '#if HAS_INSTANCES',
    recordGlsl(INSTANCE, 'instanceTexel'),
    '#endif',
  ].join('\n');
}
