/**
 * The validated, normalized scene model (scene format version 1).
 * Every color here is linear RGB; every default of the format is filled in.
 * `parseScene` (schema.ts) is the only way untrusted JSON becomes a `Scene`.
 */
export type Vec3 = [number, number, number];

export interface Material {
  /** Linear albedo, each channel in [0, 1]. */
  color: Vec3;
  /** 0 = ideal mirror, 1 = Lambertian; the BSDF blends GGX (alpha = r^2) and Lambert. */
  roughness: number;
}

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

export interface Environment {
  color: Vec3;
  intensity: number;
}

export interface Ground {
  height: number;
  material: Material;
}

export interface Light {
  position: Vec3;
  radius: number;
  color: Vec3;
  intensity: number;
}

export interface Sphere {
  center: Vec3;
  radius: number;
  material: Material;
}

export interface Scene {
  version: 1;
  camera: Camera;
  image: ImageSize;
  render: RenderSettings;
  /** null = black: escaping rays carry no radiance. */
  environment: Environment | null;
  /** null = no ground plane. */
  ground: Ground | null;
  lights: Light[];
  spheres: Sphere[];
}

/**
 * An equirectangular (latitude-longitude) environment image of linear RGB
 * radiance: `rgb` holds width * height * 3 floats, row 0 at the top (the
 * zenith), each row from u = 0 (left) to u = 1. Decoded from `.hdr`/`.exr`
 * by src/scene/envmap/; every value finite and >= 0.
 */
export interface EnvironmentImage {
  width: number;
  height: number;
  rgb: Float32Array;
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
}
