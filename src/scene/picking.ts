/**
 * Picking on the CPU against the scene model: which sphere or light (or the
 * ground) a camera ray hits first, and where a world point lands on the image.
 * Rays come from `cameraRay`, the shader's own central ray, so a click selects
 * exactly what is drawn under the cursor. Pure: no DOM, no GL.
 */
import { cameraFrame, cameraRay, type Ray } from './camera';
import { inverseAffine, meshToWorldMatrix } from './mesh/transform';
import type { Camera, Mesh, Scene, TriangleMesh, Vec3 } from './types';
import { lightExtent } from '../lights/registry';

/** Radius of the sphere that picks a light with no size of its own. */
export const LIGHT_PICK_RADIUS = 0.1;

export type ObjectKind = 'sphere' | 'light' | 'mesh';

/** The decoded triangles of a mesh file by its name as written (undefined: not loaded, not pickable). */
export type MeshLookup = (file: string) => TriangleMesh | undefined;

export interface ObjectHit {
  kind: ObjectKind;
  index: number;
  /** Distance along the (unit) ray direction. */
  t: number;
  point: Vec3;
}

export type SurfaceHit = ObjectHit | { kind: 'ground'; index: -1; t: number; point: Vec3 };

/** Ignore hits closer than this (a ray starting on a surface). */
const T_MIN = 1e-6;

/** Nearest t > T_MIN where the ray meets the sphere, or null. From inside, the exit point. */
export function intersectSphere(ray: Ray, center: Vec3, radius: number): number | null {
  const o = sub(ray.origin, center);
  const b = dot(o, ray.direction);
  const c = dot(o, o) - radius * radius;
  const disc = b * b - c * dot(ray.direction, ray.direction);
  if (disc < 0) return null;
  const a = dot(ray.direction, ray.direction);
  const root = Math.sqrt(disc);
  const near = (-b - root) / a;
  if (near > T_MIN) return near;
  const far = (-b + root) / a;
  return far > T_MIN ? far : null;
}

/** t where the ray meets the horizontal plane y = height (from either side), or null. */
export function intersectPlaneY(ray: Ray, height: number): number | null {
  const dy = ray.direction[1];
  if (Math.abs(dy) < 1e-12) return null;
  const t = (height - ray.origin[1]) / dy;
  return t > T_MIN ? t : null;
}

/** The nearest sphere, light or mesh on the ray (meshes only with `meshes`); the ground hides what is below it. */
export function pickObject(scene: Scene, ray: Ray, meshes?: MeshLookup): ObjectHit | null {
  let best: ObjectHit | null = null;
  const consider = (kind: ObjectKind, index: number, center: Vec3, radius: number) => {
    const t = intersectSphere(ray, center, radius);
    if (t !== null && (best === null || t < best.t)) best = { kind, index, t, point: along(ray, t) };
  };
  scene.spheres.forEach((s, i) => consider('sphere', i, s.center, s.radius));
  // A light is picked by the sphere around it (LIGHT_PICK_RADIUS at least; a light with no extent, none).
  scene.lights.forEach((l, i) => {
    const extent = lightExtent(l);
    if (extent) consider('light', i, extent.center, Math.max(extent.radius, LIGHT_PICK_RADIUS));
  });
  scene.meshes.forEach((mesh, i) => {
    const data = meshes?.(mesh.file);
    const t = data ? intersectMesh(ray, mesh, data) : null;
    if (t !== null && (best === null || t < best.t)) best = { kind: 'mesh', index: i, t, point: along(ray, t) };
  });
  const ground = groundT(scene, ray);
  const hit = best as ObjectHit | null;
  // An object below the ground plane is hidden by it, as in the render.
  if (hit && ground !== null && ground < hit.t) return null;
  return hit;
}

/** The nearest visible surface on the ray, the ground included (for focusing). */
export function pickSurface(scene: Scene, ray: Ray, meshes?: MeshLookup): SurfaceHit | null {
  const object = pickObject(scene, ray, meshes);
  if (object) return object;
  const t = groundT(scene, ray);
  return t === null ? null : { kind: 'ground', index: -1, t, point: along(ray, t) };
}

/** Picks at image point (u right, v down, in [0, 1]) for an image of the given aspect (width / height). */
export function pickAt(scene: Scene, aspect: number, u: number, v: number, meshes?: MeshLookup): ObjectHit | null {
  return pickObject(scene, cameraRay(scene.camera, aspect, u, v), meshes);
}

export interface Projection {
  /** Image coordinates: u right, v down, in [0, 1] inside the image. */
  u: number;
  v: number;
  /** Distance in front of the camera along its view direction. */
  depth: number;
}

/** Where a world point lands on the image, or null when it is behind the camera. */
export function projectPoint(camera: Camera, aspect: number, point: Vec3): Projection | null {
  const frame = cameraFrame(camera);
  const d = sub(point, frame.position);
  const depth = dot(d, frame.forward);
  if (depth <= 1e-9) return null;
  const tanHalf = Math.tan((camera.fov * Math.PI) / 360);
  const x = dot(d, frame.right) / (depth * tanHalf * aspect);
  const y = dot(d, frame.up) / (depth * tanHalf);
  return { u: (x + 1) / 2, v: (1 - y) / 2, depth };
}

/**
 * The projected outline of a sphere, approximated by a circle: its centre in
 * image coordinates and its radius as a fraction of the image height.
 */
export function projectSphere(
  camera: Camera,
  aspect: number,
  center: Vec3,
  radius: number,
): (Projection & { radius: number }) | null {
  const p = projectPoint(camera, aspect, center);
  if (!p) return null;
  const tanHalf = Math.tan((camera.fov * Math.PI) / 360);
  const apparent = radius / Math.sqrt(Math.max(p.depth * p.depth - radius * radius, 1e-12));
  return { ...p, radius: Math.min(apparent / (2 * tanHalf), 10) };
}

/** Object-space bounds per decoded mesh (computed once: picking tests the box before any triangle). */
const boundsCache = new WeakMap<TriangleMesh, { min: Vec3; max: Vec3 }>();

export function meshBounds(data: TriangleMesh): { min: Vec3; max: Vec3 } {
  let bounds = boundsCache.get(data);
  if (!bounds) {
    const min: Vec3 = [Infinity, Infinity, Infinity];
    const max: Vec3 = [-Infinity, -Infinity, -Infinity];
    const p = data.positions;
    for (let i = 0; i < p.length; i += 3) {
      for (let k = 0; k < 3; k++) {
        if (p[i + k] < min[k]) min[k] = p[i + k];
        if (p[i + k] > max[k]) max[k] = p[i + k];
      }
    }
    boundsCache.set(data, (bounds = { min, max }));
  }
  return bounds;
}

/**
 * Nearest t > T_MIN where the ray meets the placed mesh (either side of a
 * triangle), or null. The ray goes into object space (t is unchanged by an
 * affine map), is tested against the object-space box, then against every
 * triangle (Moller-Trumbore): a click is rare, so no BVH is kept here.
 */
export function intersectMesh(ray: Ray, mesh: Mesh, data: TriangleMesh): number | null {
  const inverse = inverseAffine(meshToWorldMatrix(mesh));
  const o = transformPoint(inverse, ray.origin, 1);
  const d = transformPoint(inverse, ray.direction, 0);
  const { min, max } = meshBounds(data);
  if (!hitsBox(o, d, min, max)) return null;
  const p = data.positions;
  const idx = data.indices;
  let best = Infinity;
  for (let i = 0; i < idx.length; i += 3) {
    const t = intersectTriangle(o, d, p, idx[i] * 3, idx[i + 1] * 3, idx[i + 2] * 3);
    if (t > T_MIN && t < best) best = t;
  }
  return best < Infinity ? best : null;
}

function intersectTriangle(o: Vec3, d: Vec3, p: Float32Array, a: number, b: number, c: number): number {
  const e1x = p[b] - p[a], e1y = p[b + 1] - p[a + 1], e1z = p[b + 2] - p[a + 2];
  const e2x = p[c] - p[a], e2y = p[c + 1] - p[a + 1], e2z = p[c + 2] - p[a + 2];
  const px = d[1] * e2z - d[2] * e2y, py = d[2] * e2x - d[0] * e2z, pz = d[0] * e2y - d[1] * e2x;
  const det = e1x * px + e1y * py + e1z * pz;
  if (det === 0) return NaN;
  const inv = 1 / det;
  const sx = o[0] - p[a], sy = o[1] - p[a + 1], sz = o[2] - p[a + 2];
  const u = (sx * px + sy * py + sz * pz) * inv;
  if (u < 0 || u > 1) return NaN;
  const qx = sy * e1z - sz * e1y, qy = sz * e1x - sx * e1z, qz = sx * e1y - sy * e1x;
  const v = (d[0] * qx + d[1] * qy + d[2] * qz) * inv;
  if (v < 0 || u + v > 1) return NaN;
  return (e2x * qx + e2y * qy + e2z * qz) * inv;
}

function hitsBox(o: Vec3, d: Vec3, min: Vec3, max: Vec3): boolean {
  let enter = 0;
  let exit = Infinity;
  for (let k = 0; k < 3; k++) {
    const inv = 1 / d[k];
    const t0 = (min[k] - o[k]) * inv;
    const t1 = (max[k] - o[k]) * inv;
    if (Number.isNaN(t0) || Number.isNaN(t1)) continue; // parallel to the slab, on its boundary: keep testing
    enter = Math.max(enter, Math.min(t0, t1));
    exit = Math.min(exit, Math.max(t0, t1));
  }
  return enter <= exit * 1.000001;
}

const transformPoint = (m: Float64Array, v: Vec3, w: 0 | 1): Vec3 => [
  m[0] * v[0] + m[4] * v[1] + m[8] * v[2] + w * m[12],
  m[1] * v[0] + m[5] * v[1] + m[9] * v[2] + w * m[13],
  m[2] * v[0] + m[6] * v[1] + m[10] * v[2] + w * m[14],
];

function groundT(scene: Scene, ray: Ray): number | null {
  if (!scene.ground) return null;
  // Only the upper side is lit and seen from above; a camera below still hits it.
  return intersectPlaneY(ray, scene.ground.height);
}

const sub = (a: Vec3, b: Vec3): Vec3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a: Vec3, b: Vec3): number => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const along = (ray: Ray, t: number): Vec3 => [
  ray.origin[0] + t * ray.direction[0],
  ray.origin[1] + t * ray.direction[1],
  ray.origin[2] + t * ray.direction[2],
];
