/**
 * Camera math shared by the renderer (uniforms) and the page (picking), so a
 * ray cast on the CPU goes exactly where the shader's central ray goes.
 */
import { mat4, vec3, vec4 } from 'gl-matrix';
import type { Camera, Vec3 } from './types';

export interface CameraFrame {
  position: Vec3;
  /** Unit vector from position towards target. */
  forward: Vec3;
  /** Image right: normalize(cross(forward, up)). */
  right: Vec3;
  /** Image up, orthogonal to forward and right. */
  up: Vec3;
  focusDistance: number;
}

export interface Ray {
  origin: Vec3;
  direction: Vec3;
}

const FALLBACK_UPS: Vec3[] = [[0, 1, 0], [0, 0, -1], [1, 0, 0]];

/**
 * Orthonormal camera frame. When `up` is (nearly) parallel to the view
 * direction the image's up would be undefined; we then fall back to the first
 * of +y, -z, +x that is not, so looking straight up or down still renders.
 */
export function cameraFrame(camera: Camera): CameraFrame {
  const forward = vec3.sub(vec3.create(), camera.target, camera.position);
  const distance = vec3.length(forward);
  vec3.scale(forward, forward, 1 / distance);
  const right = vec3.create();
  for (const up of [camera.up, ...FALLBACK_UPS]) {
    vec3.cross(right, forward, up);
    if (vec3.length(right) > 1e-6 * Math.max(1e-30, vec3.length(up))) break;
  }
  vec3.normalize(right, right);
  const up = vec3.cross(vec3.create(), right, forward);
  return {
    position: [...camera.position] as Vec3,
    forward: toVec3(forward),
    right: toVec3(right),
    up: toVec3(up),
    focusDistance: camera.focusDistance ?? distance,
  };
}

/**
 * Inverse of projection * rotation-only view: maps an NDC point to a world
 * direction (relative to the camera position). Keeping the translation out
 * keeps the matrix well conditioned for cameras far from the origin.
 */
export function inverseViewProjection(camera: Camera, aspect: number): mat4 {
  const frame = cameraFrame(camera);
  const view = mat4.fromValues(
    frame.right[0], frame.up[0], -frame.forward[0], 0,
    frame.right[1], frame.up[1], -frame.forward[1], 0,
    frame.right[2], frame.up[2], -frame.forward[2], 0,
    0, 0, 0, 1,
  );
  const projection = mat4.perspective(mat4.create(), (camera.fov * Math.PI) / 180, aspect, 1, Infinity);
  const viewProjection = mat4.multiply(mat4.create(), projection, view);
  return mat4.invert(mat4.create(), viewProjection) as mat4;
}

/**
 * The pinhole ray through image point (u, v), u rightwards and v downwards in
 * [0, 1] (row 0 is the image's top), as the shader computes it without jitter.
 */
export function cameraRay(camera: Camera, aspect: number, u: number, v: number): Ray {
  const inverse = inverseViewProjection(camera, aspect);
  const ndc = vec4.fromValues(2 * u - 1, 1 - 2 * v, -1, 1);
  const point = vec4.transformMat4(vec4.create(), ndc, inverse);
  const direction = vec3.fromValues(point[0] / point[3], point[1] / point[3], point[2] / point[3]);
  vec3.normalize(direction, direction);
  return { origin: [...camera.position] as Vec3, direction: toVec3(direction) };
}

function toVec3(v: ArrayLike<number>): Vec3 {
  return [v[0], v[1], v[2]];
}
