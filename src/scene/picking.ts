/**
 * Picking on the CPU against the scene model: which sphere or light (or the
 * ground) a camera ray hits first, and where a world point lands on the image.
 * Rays come from `cameraRay`, the shader's own central ray, so a click selects
 * exactly what is drawn under the cursor. Pure: no DOM, no GL.
 */
import { cameraFrame, cameraRay, type Ray } from './camera';
import type { Camera, Scene, Vec3 } from './types';

export type ObjectKind = 'sphere' | 'light';

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

/** The nearest sphere or light on the ray (the ground does not hide objects behind it here). */
export function pickObject(scene: Scene, ray: Ray): ObjectHit | null {
  let best: ObjectHit | null = null;
  const consider = (kind: ObjectKind, index: number, center: Vec3, radius: number) => {
    const t = intersectSphere(ray, center, radius);
    if (t !== null && (best === null || t < best.t)) best = { kind, index, t, point: along(ray, t) };
  };
  scene.spheres.forEach((s, i) => consider('sphere', i, s.center, s.radius));
  scene.lights.forEach((l, i) => consider('light', i, l.position, l.radius));
  const ground = groundT(scene, ray);
  const hit = best as ObjectHit | null;
  // An object below the ground plane is hidden by it, as in the render.
  if (hit && ground !== null && ground < hit.t) return null;
  return hit;
}

/** The nearest visible surface on the ray, the ground included (for focusing). */
export function pickSurface(scene: Scene, ray: Ray): SurfaceHit | null {
  const object = pickObject(scene, ray);
  if (object) return object;
  const t = groundT(scene, ray);
  return t === null ? null : { kind: 'ground', index: -1, t, point: along(ray, t) };
}

/** Picks at image point (u right, v down, in [0, 1]) for an image of the given aspect (width / height). */
export function pickAt(scene: Scene, aspect: number, u: number, v: number): ObjectHit | null {
  return pickObject(scene, cameraRay(scene.camera, aspect, u, v));
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
