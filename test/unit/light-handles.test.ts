/**
 * The light handles' math (src/app/lightHandles.ts): the handles' places,
 * the plane facing the camera, the wrapped sphere an aim drag turns on, the
 * rotation that aims a planar light (its spin kept), and what a drag from a
 * handle to a cursor ray does to each kind.
 */
import { describe, expect, it } from 'vitest';
import { cameraFrame, type Ray } from '../../src/scene/camera';
import { meshToWorldMatrix } from '../../src/scene/mesh/transform';
import type { Camera, Vec3 } from '../../src/scene/types';
import { createLight, type Light } from '../../src/lights/registry';
import {
  aimRotation,
  draggedLight,
  emitDirection,
  eulerAngles,
  handleNear,
  handlePoints,
  markerNear,
  sunMarkers,
  viewPlanePoint,
  wrapSphere,
  type HandleDrag,
  type HandleKind,
} from '../../src/app/lightHandles';
import { random } from '../support/random';

const camera: Camera = { position: [1, 2, 6], target: [0, 0.5, 0], up: [0, 1, 0], fov: 40, aperture: 0 };
const frame = cameraFrame(camera);

/** The camera ray through the pixel where `p` is seen (in double precision: cameraRay's are float32). */
function rayThrough(p: Vec3): Ray {
  return { origin: camera.position, direction: unit(sub(p, camera.position)) };
}
const add = (a: Vec3, b: Vec3): Vec3 => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const sub = (a: Vec3, b: Vec3): Vec3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const scale = (a: Vec3, s: number): Vec3 => [a[0] * s, a[1] * s, a[2] * s];
const dot = (a: Vec3, b: Vec3) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const norm = (a: Vec3) => Math.hypot(...a);
const unit = (a: Vec3) => scale(a, 1 / norm(a));
const expectVec = (actual: readonly number[], expected: readonly number[], digits = 6) =>
  actual.forEach((x, i) => expect(x, `component ${i} of [${actual}] against [${expected}]`).toBeCloseTo(expected[i], digits));
const rotationOf = (angles: Vec3) => Array.from(meshToWorldMatrix({ rotation: angles })).filter((_, i) => i % 4 !== 3 && i < 12);
const dragOf = (kind: HandleKind, light: Light, from: Vec3): HandleDrag => ({ kind, index: 0, light, camera, start: rayThrough(from) });

describe('handle places', () => {
  it('every positioned kind has a move handle on its position; spot, rectangle, disk and directional an aim handle', () => {
    const has = Object.fromEntries(
      (['sphere', 'point', 'spot', 'rectangle', 'disk', 'directional'] as const).map((type) => {
        const h = handlePoints(createLight(type, [0, 0, 0]), camera);
        return [type, [h.move !== null, h.aim !== null]];
      }),
    );
    expect(has).toEqual({
      sphere: [true, false], point: [true, false], spot: [true, true], rectangle: [true, true], disk: [true, true], directional: [false, true],
    });
  });

  it("puts a spot's aim on its target, a planar light's on its emitting axis, a directional light's up its light around the camera's target", () => {
    const spot = createLight('spot', [0, 0, 0]) as Extract<Light, { type: 'spot' }>;
    expect(handlePoints(spot, camera).aim).toEqual(spot.target);
    const disk = { ...(createLight('disk', [0, 0, 0]) as Extract<Light, { type: 'disk' }>), rotation: [30, 0, 0] as Vec3 };
    const h = handlePoints(disk, camera);
    expectVec(unit(sub(h.aim!, disk.position)), emitDirection(disk.rotation));
    const sun: Light = { type: 'directional', direction: [0, -2, 0], color: [1, 1, 1], irradiance: 1 };
    const s = handlePoints(sun, camera);
    expect(s.origin).toEqual(camera.target);
    expectVec(unit(sub(s.aim!, camera.target)), [0, 1, 0]);
  });

  it('grabs the nearest handle within reach, none beyond it', () => {
    const handles = { move: { x: 100, y: 100 }, aim: { x: 106, y: 100 } };
    expect(handleNear(handles, 101, 100, 9)).toBe('move');
    expect(handleNear(handles, 105, 101, 9)).toBe('aim');
    expect(handleNear(handles, 120, 100, 9)).toBeNull();
    expect(handleNear({ aim: undefined, move: { x: 0, y: 0 } }, 3, 4, 5)).toBe('move');
  });

  it("marks every directional light, and only those, where its aim handle goes, selected or not", () => {
    const sun = (direction: Vec3): Light => ({ type: 'directional', direction, color: [1, 1, 1], irradiance: 1 });
    const lights = [createLight('spot', [0, 0, 0]), sun([0, -1, 0]), createLight('point', [1, 1, 1]), sun([1, -1, 0.5])];
    const markers = sunMarkers(lights, camera);
    expect(markers.map((m) => m.index)).toEqual([1, 3]);
    for (const m of markers) expect(m.point).toEqual(handlePoints(lights[m.index], camera).aim);
    expect(sunMarkers([createLight('rectangle', [0, 0, 0])], camera)).toEqual([]);
  });

  it('finds the marker nearest the cursor within reach, the one drawn on top of two in the same place, none beyond', () => {
    const markers = [{ index: 2, x: 50, y: 50 }, { index: 5, x: 58, y: 50 }, { index: 7, x: 58, y: 50 }];
    expect(markerNear(markers, 52, 51, 9)).toBe(2);
    expect(markerNear(markers, 56, 50, 9), 'of two in the same place, the later (drawn on top)').toBe(7);
    expect(markerNear(markers, 40, 40, 9)).toBeNull();
    expect(markerNear([], 0, 0, 9)).toBeNull();
  });
});

describe('the plane facing the camera and the wrapped sphere', () => {
  it('meets a ray where it crosses the plane through the point, at that point\'s depth', () => {
    const through: Vec3 = [0.3, 1.2, -0.4];
    const target: Vec3 = add(through, add(scale(frame.right, 0.7), scale(frame.up, -0.2)));
    const hit = viewPlanePoint(camera, rayThrough(target), through)!;
    expectVec(hit, target);
    // Near the horizon of that plane the point would fly off: none.
    const away = { origin: camera.position, direction: unit(add(frame.right, scale(frame.forward, 1e-4))) };
    expect(viewPlanePoint(camera, away, through)).toBeNull();
  });

  it('meets the sphere on the half asked for, goes on over the rim to the other pole, on the sphere and continuous', () => {
    const center: Vec3 = [0, 1, 0];
    const r = 0.5;
    const towards = unit(sub(camera.position, center));
    const near = wrapSphere(rayThrough(center), center, r);
    expectVec(near, add(center, scale(towards, r)));
    expectVec(wrapSphere(rayThrough(center), center, r, false), sub(center, scale(towards, r)));
    // A point on either half, seen through its own pixel, is that point (grabbing a handle leaves it).
    const onSphere = add(center, scale(unit([0.3, 0.8, 0.2]), r));
    const front = dot(sub(onSphere, center), sub(onSphere, camera.position)) <= 0;
    expectVec(wrapSphere(rayThrough(onSphere), center, r, front), onSphere);
    let previous: Vec3 | null = null;
    let last: Vec3 = near;
    for (let s = 0; s <= 2.5; s += 0.01) {
      const p = wrapSphere(rayThrough(add(center, scale(frame.right, s * r))), center, r);
      expect(norm(sub(p, center))).toBeCloseTo(r, 9);
      if (previous) expect(norm(sub(p, previous)), `jump at ${s.toFixed(2)} radii`).toBeLessThan(0.1 * r);
      previous = last = p;
    }
    expect(dot(unit(sub(last, center)), towards), 'well past the rim: about the back pole').toBeLessThan(-0.95);
  });
});

describe('aiming a planar light', () => {
  it('turns the emitting axis onto any direction', () => {
    const next = random(7);
    for (let i = 0; i < 200; i++) {
      const rotation: Vec3 = [next() * 720 - 360, next() * 180 - 90, next() * 720 - 360];
      const direction: Vec3 = [next() * 2 - 1, next() * 2 - 1, next() * 2 - 1];
      expectVec(emitDirection(aimRotation(rotation, direction)), unit(direction));
    }
  });

  it('keeps the rotation when the axis is already there, and the spin about the axis by the least turn', () => {
    const rotation: Vec3 = [20, 35, -70];
    expectVec(rotationOf(aimRotation(rotation, emitDirection(rotation))), rotationOf(rotation));
    // Straight down with a spin of 40 degrees about y, turned to point along -z: the light's x axis (which the turn,
    // about the world x axis, leaves alone) stays where it was.
    const spun: Vec3 = [0, 40, 0];
    const turned = aimRotation(spun, [0, 0, -1]);
    const xAxis = (angles: Vec3) => rotationOf(angles).slice(0, 3);
    expectVec(emitDirection(turned), [0, 0, -1]);
    expect(dot(xAxis(turned) as Vec3, [1, 0, 0])).toBeCloseTo(dot(xAxis(spun) as Vec3, [1, 0, 0]), 9);
    // Opposite: half a turn, still an exact aim.
    expectVec(emitDirection(aimRotation([0, 0, 0], [0, 1, 0])), [0, 1, 0]);
  });

  it('reads the angles back from a matrix, also at gimbal lock', () => {
    for (const angles of [[10, 20, 30], [-170, 89, 45], [33, 90, 0], [33, -90, 0], [0, 0, 180]] as Vec3[]) {
      const m = meshToWorldMatrix({ rotation: angles });
      const rows = [0, 1, 2].map((r) => [m[r], m[4 + r], m[8 + r]]) as [Vec3, Vec3, Vec3];
      expectVec(rotationOf(eulerAngles(rows)), rotationOf(angles));
    }
  });
});

describe('dragging a handle', () => {
  it('moves a light with the cursor in the plane facing the camera', () => {
    const light = createLight('point', [0, 0, 0]) as Extract<Light, { type: 'point' }>;
    const offset = add(scale(frame.right, 0.4), scale(frame.up, 0.25));
    const moved = draggedLight(dragOf('move', light, light.position), rayThrough(add(light.position, offset)), null)!;
    expectVec((moved as { position: Vec3 }).position, add(light.position, offset));
  });

  it("puts a spot's target on the surface under the cursor, else in the plane facing the camera", () => {
    const spot = createLight('spot', [0, 0, 0]) as Extract<Light, { type: 'spot' }>;
    const drag = dragOf('aim', spot, spot.target);
    expect(draggedLight(drag, rayThrough([1, 0, 0]), [1, 0, 0.5])).toEqual({ target: [1, 0, 0.5] });
    const inPlane = add(spot.target, scale(frame.up, 0.3));
    expectVec((draggedLight(drag, rayThrough(inPlane), null) as { target: Vec3 }).target, inPlane);
    expect(draggedLight(drag, rayThrough(spot.position), spot.position), 'a target on the position is no axis').toBeNull();
  });

  it('aims a rectangle at the surface under the cursor, and grabbing its handle leaves it as it was on either half', () => {
    for (const rotation of [[0, 0, 0], [180, 0, 0], [-60, 30, 0]] as Vec3[]) {
      const light = { ...(createLight('rectangle', [0, 0, 0]) as Extract<Light, { type: 'rectangle' }>), rotation };
      const aim = handlePoints(light, camera).aim!;
      const grabbed = draggedLight(dragOf('aim', light, aim), rayThrough(aim), null) as { rotation: Vec3 };
      expectVec(emitDirection(grabbed.rotation), emitDirection(rotation));
      const surface: Vec3 = [0.5, 0, 0.2];
      const aimed = draggedLight(dragOf('aim', light, aim), rayThrough(surface), surface) as { rotation: Vec3 };
      expectVec(emitDirection(aimed.rotation), unit(sub(surface, light.position)));
    }
  });

  it("turns a directional light with its handle; the cursor on the camera's target makes it light the view head on", () => {
    const sun: Light = { type: 'directional', direction: [-0.3, -1, -0.4], color: [1, 1, 1], irradiance: 1 };
    const aim = handlePoints(sun, camera).aim!;
    const grabbed = draggedLight(dragOf('aim', sun, aim), rayThrough(aim), null) as { direction: Vec3 };
    expectVec(grabbed.direction, unit(sun.direction));
    const front = draggedLight(dragOf('aim', sun, aim), rayThrough(camera.target), null) as { direction: Vec3 };
    expectVec(front.direction, frame.forward);
    expect(draggedLight(dragOf('move', sun, aim), rayThrough(camera.target), null), 'no position to move').toBeNull();
  });
});
