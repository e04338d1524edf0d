import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { cameraFrame, cameraRay, type Camera, type Vec3 } from '../../src/scene';

const dot = (a: Vec3, b: Vec3) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a: Vec3, b: Vec3): Vec3 => [
  a[1] * b[2] - a[2] * b[1],
  a[2] * b[0] - a[0] * b[2],
  a[0] * b[1] - a[1] * b[0],
];
const length = (a: Vec3) => Math.sqrt(dot(a, a));
const normalize = (a: Vec3): Vec3 => a.map((x) => x / length(a)) as Vec3;
const angleDegrees = (a: Vec3, b: Vec3) =>
  (Math.acos(Math.min(1, dot(a, b) / (length(a) * length(b)))) * 180) / Math.PI;

/**
 * camera.ts computes with gl-matrix, whose vectors are Float32Arrays: results
 * are as precise as the shader's 32-bit floats (about 1e-7), not more.
 */
const DIGITS = 6;

const camera = (overrides: Partial<Camera> = {}): Camera => ({
  position: [0, 2, 8],
  target: [1, 0.5, 0],
  up: [0, 1, 0],
  fov: 40,
  aperture: 0,
  ...overrides,
});

function expectOrthonormal(frame: ReturnType<typeof cameraFrame>) {
  for (const v of [frame.forward, frame.right, frame.up]) {
    for (const x of v) expect(Number.isFinite(x)).toBe(true);
    expect(length(v)).toBeCloseTo(1, DIGITS);
  }
  expect(dot(frame.forward, frame.right)).toBeCloseTo(0, DIGITS);
  expect(dot(frame.forward, frame.up)).toBeCloseTo(0, DIGITS);
  expect(dot(frame.right, frame.up)).toBeCloseTo(0, DIGITS);
  // Right-handed: right x up = -forward, i.e. the camera looks down its -z.
  const back = cross(frame.right, frame.up);
  for (let i = 0; i < 3; i++) expect(back[i]).toBeCloseTo(-frame.forward[i], DIGITS);
}

const expectVec = (actual: Vec3, expected: Vec3, digits = DIGITS) => {
  for (let i = 0; i < 3; i++) expect(actual[i]).toBeCloseTo(expected[i], digits);
};

describe('cameraFrame', () => {
  it('is orthonormal, with right = normalize(cross(forward, up))', () => {
    const cam = camera();
    const frame = cameraFrame(cam);
    expectOrthonormal(frame);
    expectVec(frame.forward, normalize([1, -1.5, -8]));
    expectVec(frame.right, normalize(cross(frame.forward, cam.up)));
    expect(dot(frame.up, cam.up)).toBeGreaterThan(0);
  });

  it('is orthonormal for random cameras', () => {
    const coordinate = fc.double({ min: -100, max: 100, noNaN: true });
    const point = fc.tuple(coordinate, coordinate, coordinate);
    fc.assert(
      fc.property(point, point, point, (position, target, up) => {
        fc.pre(length([target[0] - position[0], target[1] - position[1], target[2] - position[2]]) > 1e-3);
        fc.pre(length(up) > 1e-3);
        const frame = cameraFrame(camera({ position, target, up }));
        expectOrthonormal(frame);
        // Where up is not nearly parallel to the view, right follows the definition exactly.
        const side = cross(frame.forward, up);
        if (length(side) > 1e-3 * length(up)) expectVec(frame.right, normalize(side));
      }),
      { numRuns: 300 },
    );
  });

  it('takes focusDistance from the target unless it is given', () => {
    expect(cameraFrame(camera({ position: [0, 0, 5], target: [0, 0, 1] })).focusDistance).toBeCloseTo(4, 14);
    expect(cameraFrame(camera({ focusDistance: 2.5 })).focusDistance).toBe(2.5);
  });

  it.each([
    ['looking straight down', [0, 5, 0], [0, 0, 0], [0, 1, 0]],
    ['looking straight up', [0, 0, 0], [0, 5, 0], [0, 1, 0]],
    ['with up opposite to the view', [0, 0, 0], [0, 5, 0], [0, -2, 0]],
    ['along -z with up = -z', [0, 0, 5], [0, 0, 0], [0, 0, -1]],
    ['along x with up = x', [0, 0, 0], [3, 0, 0], [1, 0, 0]],
    ['with up almost parallel', [0, 5, 0], [0, 0, 0], [1e-9, 1, 0]],
  ] as [string, Vec3, Vec3, Vec3][])('gives a finite orthonormal frame %s', (_, position, target, up) => {
    expectOrthonormal(cameraFrame(camera({ position, target, up })));
  });
});

describe('cameraRay', () => {
  const aspect = 4 / 3;

  it('sends the centre of the image along forward, from the camera position', () => {
    const cam = camera();
    const ray = cameraRay(cam, aspect, 0.5, 0.5);
    expect(ray.origin).toEqual(cam.position);
    expectVec(ray.direction, cameraFrame(cam).forward);
  });

  it('sends the top-right corner (u = 1, v = 0) right and up', () => {
    const cam = camera();
    const frame = cameraFrame(cam);
    const ray = cameraRay(cam, aspect, 1, 0);
    expect(dot(ray.direction, frame.right)).toBeGreaterThan(0.1);
    expect(dot(ray.direction, frame.up)).toBeGreaterThan(0.1);
    expect(dot(ray.direction, frame.forward)).toBeGreaterThan(0);
    const bottomLeft = cameraRay(cam, aspect, 0, 1).direction;
    expect(dot(bottomLeft, frame.right)).toBeLessThan(-0.1);
    expect(dot(bottomLeft, frame.up)).toBeLessThan(-0.1);
  });

  it.each([10, 40, 90, 150])('respects a vertical fov of %d degrees', (fov) => {
    const cam = camera({ fov });
    const forward = cameraFrame(cam).forward;
    expect(angleDegrees(cameraRay(cam, aspect, 0.5, 0).direction, forward)).toBeCloseTo(fov / 2, 4);
    expect(angleDegrees(cameraRay(cam, aspect, 0.5, 1).direction, forward)).toBeCloseTo(fov / 2, 4);
    // Horizontally the half-angle follows from the aspect ratio.
    const horizontal = (Math.atan(aspect * Math.tan((fov * Math.PI) / 360)) * 180) / Math.PI;
    expect(angleDegrees(cameraRay(cam, aspect, 1, 0.5).direction, forward)).toBeCloseTo(horizontal, 4);
  });

  it('returns unit directions, even for a camera far from the origin', () => {
    const cam = camera({ position: [1e6, -1e6, 1e6], target: [1e6 - 1, -1e6, 1e6] });
    for (const [u, v] of [[0, 0], [0.3, 0.7], [1, 1]]) {
      const { direction } = cameraRay(cam, aspect, u, v);
      expect(length(direction)).toBeCloseTo(1, DIGITS);
    }
    expectVec(cameraRay(cam, aspect, 0.5, 0.5).direction, [-1, 0, 0]);
  });

  it('still works when up is parallel to the view direction', () => {
    const cam = camera({ position: [0, 5, 0], target: [0, 0, 0], up: [0, 1, 0] });
    const ray = cameraRay(cam, aspect, 0.25, 0.75);
    for (const x of ray.direction) expect(Number.isFinite(x)).toBe(true);
    expectVec(cameraRay(cam, aspect, 0.5, 0.5).direction, [0, -1, 0]);
  });
});
