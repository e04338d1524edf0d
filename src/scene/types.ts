/**
 * The validated, normalized scene model (scene format versions 1 to 3).
 * Every color here is linear RGB; every default of the format is filled in.
 * `parseScene` (schema.ts) is the only way untrusted JSON becomes a `Scene`.
 */
export type Vec3 = [number, number, number];

/** Radiance `color * intensity` emitted from the outside of a surface (version 2). */
export interface Emission {
  /** The color, or a texture's scale (as a color) when `texture` is set. */
  color: Vec3;
  intensity: number;
  /** Version 3 (kinds whose emission may be textured): the color is this texture (times `color`, its scale). */
  texture?: Texture;
}

/** A material of any kind (src/materials/: one folder per kind, listed by the registry). */
export type { Material, MaterialType } from '../materials/registry';
import type { Material } from '../materials/registry';
import type { EnvironmentDistribution } from './envmap/distribution';
import type { Texture } from './texture/texture';

export interface Camera {
  position: Vec3;
  target: Vec3;
  up: Vec3;
  /** Vertical field of view in degrees. */
  fov: number;
  /** Thin-lens radius in world units; 0 = pinhole. */
  aperture: number;
  /** Distance to the plane in focus; undefined = distance from position to target. */
  focusDistance?: number;
}

export interface ImageSize {
  width: number;
  height: number;
}

export interface RenderSettings {
  /** Most scattering events on a path (Mitsuba's max_depth - 1). */
  maxBounces: number;
}

/** Constant radiance `color * intensity` for every escaping ray. */
export interface ConstantEnvironment {
  color: Vec3;
  intensity: number;
}

/** An equirectangular map (version 2), as Mitsuba's `envmap` emitter. */
export interface MapEnvironment {
  /** The file, as written in the scene (relative to the scene file's folder). */
  map: string;
  intensity: number;
  /** Degrees about +y (right-hand rule). */
  rotation: number;
}

export type Environment = ConstantEnvironment | MapEnvironment;

export interface Ground {
  height: number;
  material: Material;
}

/** A light of any kind (src/lights/: one folder per kind, listed by the registry); version 1's is the sphere. */
export type { Light, LightType } from '../lights/registry';
import type { Light } from '../lights/registry';

export interface Sphere {
  center: Vec3;
  radius: number;
  material: Material;
}

/** A triangle mesh file placed in the scene (version 2). */
export interface Mesh {
  /** The file, as written in the scene (relative to the scene file's folder). */
  file: string;
  /**
   * The material of every triangle; null (version 3 without a `material`
   * key): the file's own materials (glTF's, an OBJ's MTL), or the default
   * material for a file that has none (fileMaterials.ts resolves it).
   */
  material: Material | null;
  position: Vec3;
  /** Degrees about x, then y, then z (world axes). */
  rotation: Vec3;
  scale: Vec3;
}

export interface Scene {
  /** The document's version: at least what its keys need (see `requiredVersion`). */
  version: 1 | 2 | 3;
  camera: Camera;
  image: ImageSize;
  render: RenderSettings;
  /** null = black: escaping rays carry no radiance. */
  environment: Environment | null;
  /** null = no ground plane. */
  ground: Ground | null;
  lights: Light[];
  spheres: Sphere[];
  meshes: Mesh[];
}

/**
 * An equirectangular (latitude-longitude) environment image of linear RGB
 * radiance: `rgb` holds width * height * 3 floats, row 0 at the top (the
 * zenith), each row from u = 0 (left) to u = 1. Decoded from `.hdr`/`.exr`
 * by src/scene/envmap/; every value finite (negative texels of lossy EXR
 * files are kept, as Mitsuba keeps them).
 */
export interface EnvironmentImage {
  width: number;
  height: number;
  rgb: Float32Array;
  /**
   * Its sampling distribution (src/scene/envmap/distribution.ts), when the
   * decoder built it (the page's map worker does, off the main thread);
   * otherwise the renderer builds it once and keeps it here.
   */
  distribution?: EnvironmentDistribution;
}

/**
 * The triangles of one mesh file in its own object space (transforms of the
 * file itself, such as glTF nodes, already applied). `positions` and
 * `normals` hold 3 floats per vertex; `indices` 3 vertex indices per
 * triangle. `normals` is null when the file does not give a normal for every
 * corner (the mesh is then flat-shaded).
 */
export interface TriangleMesh {
  positions: Float32Array;
  normals: Float32Array | null;
  indices: Uint32Array;
  /**
   * Texture coordinates, 2 floats (u, v) per vertex, of the file's first set
   * (OBJ `vt` with v turned over, `v' = 1 - v`; PLY `u v`, `s t` or
   * `texture_u texture_v` as stored; glTF `TEXCOORD_0` as stored); null when
   * the file does not give coordinates for every vertex. Untouched by
   * transforms. (0, 0) is an image's top-left corner. The mesh decoders
   * always set it; absent (meshes built in code) means null.
   */
  uvs?: Float32Array | null;
  /** glTF `TEXCOORD_1`, 2 floats per vertex, when every primitive has it; null otherwise (and for other formats); absent means null. */
  uvs1?: Float32Array | null;
  /**
   * The file's tangent frame for normal maps, glTF `TANGENT`: 4 floats (x,
   * y, z, w) per vertex, in object space like `normals` (unit xyz, w = +-1),
   * meaning bitangent = cross(normal, xyz) * w, which points up the image
   * (toward decreasing v). A vertex with (0, 0, 0, 0) has none (its
   * primitive gave no TANGENT). Null when no primitive gives one, when the
   * mesh is flat (glTF ignores TANGENT without NORMAL) and for other
   * formats; absent means null. Only read, never computed, on load: the
   * renderer asks meshTangents (./mesh/tangents.ts) for the frame of the
   * meshes that need one, which computes MikkTSpace where this has none.
   */
  tangents?: Float32Array | null;
  /** glTF `COLOR_0` as linear RGB, 3 floats per vertex (white where a primitive has none); null or absent: none. */
  colors?: Float32Array | null;
  /** The file's own materials (glTF, OBJ with MTL); absent or null: it has none. */
  fileMaterials?: FileMaterials | null;
  /** What the decoder read but ignores (unsupported extensions, a light's `range`...), one line each. */
  warnings?: string[];
  /** The file's lights (glTF KHR_lights_punctual) in its object space, like `positions`. */
  lights?: Light[];
}

/**
 * A mesh file's own materials: `materials[triangles[t]]` is triangle t's.
 * Textures name their images in the file's terms: `#N` is the file's
 * embedded image N (`images`), any other name a path relative to the mesh
 * file's folder (an image beside a `.gltf` or an OBJ's MTL, URI-decoded).
 */
export interface FileMaterials {
  materials: FileMaterial[];
  /** Per triangle, the index of its material in `materials`. */
  triangles: Uint16Array;
  /** Images stored in the file (`.glb` buffer views, data URIs), by their `#N` names. */
  images: ReadonlyMap<string, EmbeddedImage>;
}

export interface FileMaterial {
  /** The file's name for it ('' when it has none). */
  name: string;
  /** The format's material it maps to (scene-format "glTF materials"; an MTL's keys). */
  material: Material;
  /** The texture coordinate set every texture of it reads: 0 (`uvs`) or 1 (`uvs1`). */
  uvSet: 0 | 1;
  /** Whether its baseColor is multiplied by the vertex colors (glTF COLOR_0). */
  vertexColors: boolean;
}

export interface EmbeddedImage {
  bytes: Uint8Array;
  /** As the file declares it (`image/png`, `image/jpeg`, `image/ktx2`...), '' when it does not. */
  mimeType: string;
}
