/** Small vector helpers the light kinds share (double precision, plain tuples). */
import { meshToWorldMatrix } from '../scene/mesh/transform';
import type { Vec3 } from '../scene/types';

export const luminance = (c: Vec3) => 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
export const scale = (v: Vec3, s: number): Vec3 => [v[0] * s, v[1] * s, v[2] * s];
export const sub = (a: Vec3, b: Vec3): Vec3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
export const norm = (v: Vec3) => Math.hypot(v[0], v[1], v[2]);
export const normalize = (v: Vec3): Vec3 => scale(v, 1 / norm(v));
export const vec = (v: readonly number[]): Vec3 => [v[0], v[1], v[2]];
export const toRadians = (degrees: number) => (degrees * Math.PI) / 180;

/** `v` turned by the format's rotation (degrees about x, then y, then z, world axes: Rz * Ry * Rx), as meshes are. */
export function rotate(rotation: Vec3, v: Vec3): Vec3 {
  const m = meshToWorldMatrix({ rotation });
  return [0, 1, 2].map((row) => m[row] * v[0] + m[4 + row] * v[1] + m[8 + row] * v[2]) as Vec3;
}

export const dot = (a: Vec3, b: Vec3) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
export const cross = (a: Vec3, b: Vec3): Vec3 => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];

/**
 * The reach of a one-sided planar emitter of radiance `radiance` (the area
 * kinds): a facing point at distance d gets about L area / d^2; it lights
 * only the side cross(u, v) faces.
 */
export function planarReach(shape: { center: Vec3; u: Vec3; v: Vec3; area: number }, radiance: Vec3) {
  return {
    bound: { center: shape.center, radius: Math.hypot(...shape.u, ...shape.v) },
    strength: luminance(radiance) * shape.area,
    front: normalize(cross(shape.u, shape.v)),
  };
}

/** The reach of a sphere of radiance `radiance`: pi r^2 L / d^2 at distance d. */
export const sphereReach = (center: Vec3, radius: number, radiance: Vec3) => ({ bound: { center, radius }, strength: Math.PI * radius * radius * luminance(radiance) });
