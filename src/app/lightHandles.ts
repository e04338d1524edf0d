/**
 * The selected light's handles, as pure math on the scene model (no DOM, no
 * GL): where they are in the world, and what dragging one does to the light.
 *
 * - The move handle sits on the light's position (every kind with one) and
 *   moves it in the plane through it facing the camera, as Blender's grab
 *   (G) and the centre of three.js's TransformControls do: the light stays
 *   under the cursor.
 * - The aim handle: a spot's target; a rectangle's or disk's emitting axis
 *   (a point on it a fixed share of the view away); a directional light's
 *   "sun", a point on a sphere around the camera's target on the side the
 *   light comes from. A spot, rectangle or disk aims at the surface under the
 *   cursor (Blender's light gizmo tracks to what it is dragged over); over
 *   the sky a spot's target moves in the plane facing the camera and the
 *   others turn freely (wrapSphere).
 * - A directional light has no position to click, so every one, selected or
 *   not, shows a marker where its aim handle would be (sunMarkers): pressing
 *   it selects the light.
 *
 * Dragging only changes the light's keys (position, target, rotation,
 * direction): uploaded data, never a new program.
 */
import { cameraFrame, type Ray } from '../scene/camera';
import type { Camera, Vec3 } from '../scene/types';
import { meshToWorldMatrix } from '../scene/mesh/transform';
import { MIN_SPOT_AXIS } from '../lights/spot/kind';
import { lightKindOf, type Light } from '../lights/registry';

export type HandleKind = 'move' | 'aim';

/** A light's handles in the world; `origin` is where the aim line starts (the light, or a directional light's anchor). */
export interface HandlePoints {
  move: Vec3 | null;
  aim: Vec3 | null;
  origin: Vec3;
}

/** The aim handle of a rectangle, disk or directional light is this share of the image height from its origin. */
export const AIM_SHARE = 0.2;
/** A plane point farther from the handle than this many times its depth (a ray near the plane's horizon) is ignored: it would fling the light away. */
const FAR_FACTOR = 20;

/** World units per image height at the depth of `point`. */
export function viewHeightAt(camera: Camera, point: Vec3): number {
  const frame = cameraFrame(camera);
  const depth = Math.max(dot(sub(point, frame.position), frame.forward), 1e-6);
  return 2 * depth * Math.tan((camera.fov * Math.PI) / 360);
}

/** The way a rectangle or disk emits: its local -y turned by its rotation. */
export function emitDirection(rotation: Vec3): Vec3 {
  return matrixTimes(rotationMatrix(rotation), [0, -1, 0]);
}

/** What the light's aim handle drags (its kind's `aim`: src/lights/kind.ts), or undefined. */
const aimOf = (light: Light) => lightKindOf(light).aim;
/** The light's position, or null for a kind without one (a directional light). */
const positionOf = (light: Light): Vec3 | null => ('position' in light ? light.position : null);

/** A light's handles in the world (null where it has none: a directional light has no move handle, a sphere or point light no aim). */
export function handlePoints(light: Light, camera: Camera): HandlePoints {
  const position = positionOf(light);
  switch (aimOf(light)) {
    case 'target':
      return { move: position, aim: (light as { target: Vec3 }).target, origin: position! };
    case 'rotation': {
      const length = AIM_SHARE * viewHeightAt(camera, position!);
      return { move: position, aim: add(position!, scale(emitDirection((light as { rotation: Vec3 }).rotation), length)), origin: position! };
    }
    case 'direction': {
      // No position of its own: the handle circles the point the camera orbits, on the side the light comes from.
      const anchor = camera.target;
      const length = AIM_SHARE * viewHeightAt(camera, anchor);
      return { move: position, aim: sub(anchor, scale(normalize((light as { direction: Vec3 }).direction), length)), origin: anchor };
    }
    default:
      return { move: position, aim: null, origin: position! };
  }
}

/** Where the ray meets the plane through `point` with normal `normal`, or null (parallel, or behind the ray's origin). */
export function intersectPlane(ray: Ray, point: Vec3, normal: Vec3): Vec3 | null {
  const denominator = dot(ray.direction, normal);
  if (Math.abs(denominator) < 1e-12) return null;
  const t = dot(sub(point, ray.origin), normal) / denominator;
  return t > 0 ? along(ray, t) : null;
}

/** Where the ray meets the plane through `through` facing the camera; null when that is behind it or near the horizon. */
export function viewPlanePoint(camera: Camera, ray: Ray, through: Vec3): Vec3 | null {
  const forward = cameraFrame(camera).forward;
  const hit = intersectPlane(ray, through, forward);
  const depth = dot(sub(through, camera.position), forward);
  if (!hit || depth <= 0 || norm(sub(hit, through)) > FAR_FACTOR * depth) return null;
  return hit;
}

/**
 * A point on the sphere of `radius` around `center` for a cursor ray, such
 * that one drag reaches every direction. Where the ray meets the sphere, the
 * point it meets on the half the handle started on (`front`: the near one,
 * towards the camera; else the far one), so the handle stays under the
 * cursor and grabbing it does not move it. Past the rim the point goes on
 * over it onto the other half, reaching that half's pole one radius (at the
 * sphere's distance) outside the rim. Continuous in the cursor.
 */
export function wrapSphere(ray: Ray, center: Vec3, radius: number, front = true): Vec3 {
  const direction = normalize(ray.direction);
  const closest = along({ origin: ray.origin, direction }, dot(sub(center, ray.origin), direction));
  const offset = sub(closest, center);
  const distance = norm(offset);
  const side = front ? -1 : 1;
  if (distance <= radius) return add(closest, scale(direction, side * Math.sqrt(radius * radius - distance * distance)));
  // Beyond the rim: turn from the rim point (the tangent point, where the two halves meet) towards the other half's pole.
  const angle = (Math.min(1, (distance - radius) / radius) * Math.PI) / 2;
  const outward = scale(offset, 1 / distance);
  return add(center, scale(add(scale(outward, Math.cos(angle)), scale(direction, -side * Math.sin(angle))), radius));
}

/**
 * The rotation (degrees about x, then y, then z, as the format's) that turns
 * `rotation`'s emitting axis to `direction` by the least turn, so the
 * light's spin about its axis is kept.
 */
export function aimRotation(rotation: Vec3, direction: Vec3): Vec3 {
  const current = rotationMatrix(rotation);
  const from = matrixTimes(current, [0, -1, 0]);
  const to = normalize(direction);
  return eulerAngles(multiply(turnBetween(from, to, matrixTimes(current, [1, 0, 0])), current));
}

/** What a drag started: the handle, the light and the camera then (the camera does not move during a drag), the first cursor ray. */
export interface HandleDrag {
  kind: HandleKind;
  index: number;
  light: Light;
  camera: Camera;
  start: Ray;
}

/**
 * The light's keys after dragging `drag`'s handle to the cursor `ray`, or
 * null to leave it (nowhere to put it). `surface`: the visible surface
 * point under the cursor, lights left out (an aim drag aims there).
 */
export function draggedLight(drag: HandleDrag, ray: Ray, surface: Vec3 | null): Partial<Light> | null {
  const { light, camera } = drag;
  const handles = handlePoints(light, camera);
  if (drag.kind === 'move') {
    if (!handles.move || !('position' in light)) return null;
    const from = viewPlanePoint(camera, drag.start, light.position);
    const to = viewPlanePoint(camera, ray, light.position);
    return from && to ? { position: add(light.position, sub(to, from)) } : null;
  }
  const aim = aimOf(light);
  const position = positionOf(light);
  if (aim === 'target' && position) {
    const target = surface ?? viewPlanePoint(camera, ray, handles.aim!);
    return target && norm(sub(target, position)) > 1e3 * MIN_SPOT_AXIS ? { target } : null;
  }
  if (aim === 'rotation' && position) {
    const radius = norm(sub(handles.aim!, position));
    const point = surface ?? wrapSphere(ray, position, radius, facesCamera(camera, handles));
    const direction = sub(point, position);
    return norm(direction) > 1e-9 ? { rotation: aimRotation((light as { rotation: Vec3 }).rotation, direction) } : null;
  }
  if (aim === 'direction') {
    const radius = norm(sub(handles.aim!, handles.origin));
    const sun = wrapSphere(ray, handles.origin, radius, facesCamera(camera, handles));
    return { direction: normalize(sub(handles.origin, sun)) };
  }
  return null;
}

/** Whether the aim handle lies on the near half of its sphere, seen from the camera. */
function facesCamera(camera: Camera, handles: HandlePoints): boolean {
  // The near point of a ray lies before its closest approach to the centre: against the ray's direction.
  return dot(sub(handles.aim!, handles.origin), sub(handles.aim!, camera.position)) <= 0;
}

/** The handle within `radius` pixels of (x, y), the nearest if both are (points in the same pixels). */
export function handleNear(
  handles: Partial<Record<HandleKind, { x: number; y: number }>>,
  x: number,
  y: number,
  radius: number,
): HandleKind | null {
  const points = (['move', 'aim'] as const).flatMap((kind) => (handles[kind] ? [{ ...handles[kind], key: kind }] : []));
  return nearestWithin(points, x, y, radius);
}

/**
 * Where each directional light's marker is: its "sun", the place its aim
 * handle takes when it is selected. A directional light has no position to
 * click, so the marker is what selects it; shown for every one, selected or not.
 */
export function sunMarkers(lights: readonly Light[], camera: Camera): { index: number; point: Vec3 }[] {
  return lights.flatMap((light, index) => (positionOf(light) === null && aimOf(light) ? [{ index, point: handlePoints(light, camera).aim! }] : []));
}

/** The index of the marker within `radius` pixels of (x, y), the nearest if several are; null if none. */
export function markerNear(markers: readonly { index: number; x: number; y: number }[], x: number, y: number, radius: number): number | null {
  return nearestWithin(markers.map((m) => ({ ...m, key: m.index })), x, y, radius);
}

/** The key of the point nearest (x, y) within `radius`, or null; of equals the last (drawn last: on top). */
function nearestWithin<K>(points: readonly { key: K; x: number; y: number }[], x: number, y: number, radius: number): K | null {
  let best: K | null = null;
  let bestDistance = radius;
  for (const p of points) {
    const distance = Math.hypot(p.x - x, p.y - y);
    if (distance <= bestDistance) [best, bestDistance] = [p.key, distance];
  }
  return best;
}

// ---------------------------------------------------------------- rotations

type Matrix3 = [Vec3, Vec3, Vec3]; // rows

/** Rz * Ry * Rx of the format's rotation (as meshes and planar lights are turned). */
function rotationMatrix(rotation: Vec3): Matrix3 {
  const m = meshToWorldMatrix({ rotation });
  return [0, 1, 2].map((row) => [m[row], m[4 + row], m[8 + row]]) as Matrix3;
}

/** Degrees (x, y, z) with Rz(z) * Ry(y) * Rx(x) = r; at y = +-90 (gimbal lock) z is 0. */
export function eulerAngles(r: Matrix3): Vec3 {
  const degrees = (radians: number) => clean((radians * 180) / Math.PI);
  const sinY = Math.max(-1, Math.min(1, -r[2][0]));
  const y = Math.asin(sinY);
  if (Math.abs(sinY) > 1 - 1e-12) {
    const x = sinY > 0 ? Math.atan2(r[0][1], r[0][2]) : Math.atan2(-r[0][1], -r[0][2]);
    return [degrees(x), degrees(y), 0];
  }
  return [degrees(Math.atan2(r[2][1], r[2][2])), degrees(y), degrees(Math.atan2(r[1][0], r[0][0]))];
}

/** The least rotation taking unit `from` to unit `to` (Rodrigues); half a turn about `fallback` (made perpendicular) when they are opposite. */
function turnBetween(from: Vec3, to: Vec3, fallback: Vec3): Matrix3 {
  const c = dot(from, to);
  if (c < -1 + 1e-12) {
    const axis = normalize(sub(fallback, scale(from, dot(fallback, from))));
    return [0, 1, 2].map((i) => [0, 1, 2].map((j) => 2 * axis[i] * axis[j] - (i === j ? 1 : 0))) as Matrix3;
  }
  const v = cross(from, to);
  const k = 1 / (1 + c);
  return [
    [c + k * v[0] * v[0], k * v[0] * v[1] - v[2], k * v[0] * v[2] + v[1]],
    [k * v[1] * v[0] + v[2], c + k * v[1] * v[1], k * v[1] * v[2] - v[0]],
    [k * v[2] * v[0] - v[1], k * v[2] * v[1] + v[0], c + k * v[2] * v[2]],
  ];
}

const multiply = (a: Matrix3, b: Matrix3): Matrix3 =>
  [0, 1, 2].map((i) => [0, 1, 2].map((j) => a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j])) as Matrix3;
const matrixTimes = (m: Matrix3, v: Vec3): Vec3 => [dot(m[0], v), dot(m[1], v), dot(m[2], v)];

// ---------------------------------------------------------------- vectors

/** Rounds away float dust (an angle of 1e-14 degrees is 0) and -0. */
const clean = (x: number): number => (Math.abs(x) < 1e-9 ? 0 : x);
const sub = (a: Vec3, b: Vec3): Vec3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const add = (a: Vec3, b: Vec3): Vec3 => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const scale = (a: Vec3, s: number): Vec3 => [a[0] * s, a[1] * s, a[2] * s];
const dot = (a: Vec3, b: Vec3): number => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a: Vec3, b: Vec3): Vec3 => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a: Vec3): number => Math.hypot(a[0], a[1], a[2]);
const normalize = (a: Vec3): Vec3 => scale(a, 1 / norm(a));
const along = (ray: Ray, t: number): Vec3 => add(ray.origin, scale(ray.direction, t));
