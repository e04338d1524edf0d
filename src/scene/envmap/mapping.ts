/**
 * The scene format's mapping of directions to an environment map (Mitsuba
 * 3's `envmap` with to_world = rotation about +y), and its bilinear lookup,
 * in TypeScript: the reference the shader (src/shaders/lights/
 * environment_map.glsl) is tested against.
 */
import type { EnvironmentImage } from '../types';

export type Vec3 = [number, number, number];

/** Map coordinates of a world direction: u = 0.5 + atan2(-x, z) / 2 pi, v = acos(y) / pi, after undoing the rotation. */
export function directionToUv(d: Vec3, rotationDegrees: number): { u: number; v: number } {
  const a = (rotationDegrees * Math.PI) / 180;
  // Local = R_y(-rotation) * world.
  const x = Math.cos(a) * d[0] - Math.sin(a) * d[2];
  const z = Math.sin(a) * d[0] + Math.cos(a) * d[2];
  const u = 0.5 + Math.atan2(-x, z) / (2 * Math.PI);
  const v = Math.acos(Math.min(1, Math.max(-1, d[1]))) / Math.PI;
  return { u: u - Math.floor(u), v };
}

/** The world direction of map coordinates (u, v): the inverse of directionToUv. */
export function uvToDirection(u: number, v: number, rotationDegrees: number): Vec3 {
  const theta = Math.PI * v;
  const phi = 2 * Math.PI * (u - 0.5);
  const x = -Math.sin(theta) * Math.sin(phi);
  const z = Math.sin(theta) * Math.cos(phi);
  const a = (rotationDegrees * Math.PI) / 180;
  // World = R_y(rotation) * local.
  return [Math.cos(a) * x + Math.sin(a) * z, Math.cos(theta), -Math.sin(a) * x + Math.cos(a) * z];
}

/** Bilinear lookup: columns centred at (i + 0.5) / W, wrapping; rows at j / (H - 1), clamped. */
export function lookupEnvironment(image: EnvironmentImage, u: number, v: number): Vec3 {
  const { width, height, rgb } = image;
  const x = u * width - 0.5;
  const x0 = Math.floor(x);
  const tx = x - x0;
  const c0 = ((x0 % width) + width) % width;
  const c1 = (c0 + 1) % width;
  const y = Math.min(Math.max(v, 0), 1) * Math.max(height - 1, 0);
  const r0 = Math.min(Math.floor(y), Math.max(height - 2, 0));
  const ty = height > 1 ? y - r0 : 0;
  const r1 = Math.min(r0 + 1, height - 1);
  const texel = (c: number, r: number, k: number) => rgb[(r * width + c) * 3 + k];
  return [0, 1, 2].map((k) =>
    (1 - ty) * ((1 - tx) * texel(c0, r0, k) + tx * texel(c1, r0, k)) + ty * ((1 - tx) * texel(c0, r1, k) + tx * texel(c1, r1, k)),
  ) as Vec3;
}
