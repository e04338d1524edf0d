/**
 * Orbit, pan and zoom as pure functions of the scene camera: they return a new
 * camera and never touch the DOM. Orbiting keeps +y up (turntable style).
 */
import { cameraFrame } from '../scene/camera';
import type { Camera, Vec3 } from '../scene/types';

const MIN_POLAR = 0.01;
const MIN_DISTANCE = 1e-3;
const MAX_DISTANCE = 1e5;

/** Rotates the eye around the target by the given angles (radians). */
export function orbit(camera: Camera, yaw: number, pitch: number): Camera {
  const offset = sub(camera.position, camera.target);
  const radius = length(offset);
  const azimuth = Math.atan2(offset[0], offset[2]) - yaw;
  const polar = clamp(Math.acos(clamp(offset[1] / radius, -1, 1)) - pitch, MIN_POLAR, Math.PI - MIN_POLAR);
  const position: Vec3 = [
    camera.target[0] + radius * Math.sin(polar) * Math.sin(azimuth),
    camera.target[1] + radius * Math.cos(polar),
    camera.target[2] + radius * Math.sin(polar) * Math.cos(azimuth),
  ];
  return { ...camera, position, up: [0, 1, 0] };
}

/**
 * Slides eye and target in the image plane. dx, dy are fractions of the image
 * height (right and down), so the point under the cursor follows it at the target's depth.
 */
export function pan(camera: Camera, dx: number, dy: number): Camera {
  const frame = cameraFrame(camera);
  const distance = length(sub(camera.target, camera.position));
  const scale = 2 * distance * Math.tan((camera.fov * Math.PI) / 360);
  const move: Vec3 = [0, 1, 2].map((i) => scale * (-dx * frame.right[i] + dy * frame.up[i])) as Vec3;
  return { ...camera, position: add(camera.position, move), target: add(camera.target, move) };
}

/** Moves the eye towards (factor < 1) or away from (factor > 1) the target. */
export function zoom(camera: Camera, factor: number): Camera {
  const offset = sub(camera.position, camera.target);
  const distance = length(offset);
  const next = clamp(distance * factor, MIN_DISTANCE, MAX_DISTANCE);
  const position = add(camera.target, offset.map((v) => (v * next) / distance) as Vec3);
  return { ...camera, position };
}

const sub = (a: Vec3, b: Vec3): Vec3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const add = (a: Vec3, b: Vec3): Vec3 => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const length = (a: Vec3): number => Math.hypot(a[0], a[1], a[2]);
const clamp = (x: number, lo: number, hi: number): number => Math.min(hi, Math.max(lo, x));
