/**
 * The planar lights' culling groups (src/render/planarGroups.ts): the order
 * is a permutation, each group's sphere holds its members' spheres (so the
 * shader's culling can only skip what no ray through the group reaches),
 * and neighbours share groups. The culling's effect on images is checked
 * against Mitsuba by the light-many reference (references.test.ts); that
 * every point of every shape lies in its light's and its group's spheres
 * (so no ray that hits a shape is culled) is checked here on random lights.
 */
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { enclosingSphere, planarGroupBounds, planarGroupOrder, type Sphere } from '../../src/render/planarGroups';
import { lightArea, planarBound } from '../../src/lights/registry';
import { parseScene } from '../../src/scene/schema';

const sphere = fc.tuple(fc.double({ min: -50, max: 50, noNaN: true }), fc.double({ min: -50, max: 50, noNaN: true }), fc.double({ min: -50, max: 50, noNaN: true }), fc.double({ min: 1e-3, max: 5, noNaN: true }));
const spheres = fc.array(sphere, { minLength: 0, maxLength: 64 });

const contains = (outer: Sphere, inner: Sphere) =>
  Math.hypot(inner[0] - outer[0], inner[1] - outer[1], inner[2] - outer[2]) + inner[3] <= outer[3] * (1 + 1e-12);

describe('planar-light culling groups', () => {
  it('orders every light exactly once', () => {
    fc.assert(fc.property(spheres, fc.integer({ min: 1, max: 8 }), (s, size) => {
      expect([...planarGroupOrder(s, size)].sort((a, b) => a - b)).toEqual(s.map((_, i) => i));
    }));
  });

  it('gives each run of `size` lights a sphere holding all of theirs', () => {
    fc.assert(fc.property(spheres, fc.integer({ min: 1, max: 8 }), (s, size) => {
      const ordered = planarGroupOrder(s, size).map((i) => s[i]);
      const groups = planarGroupBounds(ordered, size);
      expect(groups.length).toBe(Math.ceil(s.length / size));
      ordered.forEach((member, i) => expect(contains(groups[Math.floor(i / size)], member)).toBe(true));
    }));
  });

  it('puts the lights of two far-apart clusters into separate groups', () => {
    const cluster = (x: number): Sphere[] => [0, 1, 2, 3].map((k) => [x + 0.1 * k, 2, 0.05 * k, 0.2]);
    // Interleaved in the scene's order: a split along x must regroup them.
    const lights = cluster(-10).flatMap((s, i) => [s, cluster(10)[i]]);
    const ordered = planarGroupOrder(lights, 4).map((i) => lights[i]);
    const groups = planarGroupBounds(ordered, 4);
    expect(groups.map((g) => g[3] < 1)).toEqual([true, true]);
    expect(Math.sign(groups[0][0])).toBe(-Math.sign(groups[1][0]));
  });

  it('bounds a rectangle\'s corners and a disk\'s rim with each light\'s own sphere', () => {
    const scene = parseScene({
      version: 3,
      camera: { position: [0, 1, 5], target: [0, 0, 0], fov: 40 },
      lights: [
        { type: 'rectangle', position: [1, 2, 3], rotation: [30, 40, 50], size: [2, 0.5] },
        { type: 'disk', position: [-1, 1, 0], rotation: [-20, 10, 80], radius: 0.7 },
      ],
    });
    const [rect, disk] = scene.lights.map(planarBound);
    expect(rect[3]).toBeGreaterThanOrEqual(Math.hypot(1, 0.25));
    expect(rect[3]).toBeLessThan(Math.hypot(1, 0.25) * 1.01);
    expect(disk[3]).toBeGreaterThanOrEqual(0.7);
    expect(enclosingSphere([rect, disk])[3]).toBeGreaterThan(Math.hypot(2, 1, 3) / 2);
  });

  it('never culls a ray that hits a shape: every hit point lies in its light\'s and its group\'s spheres (random lights and rays)', () => {
    const angle = fc.double({ min: -180, max: 180, noNaN: true });
    const light = fc.oneof(
      fc.record({ type: fc.constant('rectangle'), size: fc.tuple(fc.double({ min: 0.01, max: 4, noNaN: true }), fc.double({ min: 0.01, max: 4, noNaN: true })) }),
      fc.record({ type: fc.constant('disk'), radius: fc.double({ min: 0.01, max: 2, noNaN: true }) }),
    ).chain((shape) => fc.record({ position: fc.tuple(fc.double({ min: -5, max: 5, noNaN: true }), fc.double({ min: -5, max: 5, noNaN: true }), fc.double({ min: -5, max: 5, noNaN: true })), rotation: fc.tuple(angle, angle, angle) }).map((p) => ({ ...shape, ...p })));
    fc.assert(fc.property(fc.array(light, { minLength: 1, maxLength: 12 }), fc.array(fc.tuple(fc.double({ min: 0, max: 1, noNaN: true }), fc.double({ min: -1, max: 1, noNaN: true }), fc.double({ min: -1, max: 1, noNaN: true })), { minLength: 1, maxLength: 20 }), (lights, points) => {
      const scene = parseScene({ version: 3, camera: { position: [0, 1, 5], target: [0, 0, 0], fov: 40 }, lights });
      const bounds = scene.lights.map(planarBound);
      const order = planarGroupOrder(bounds, 4);
      const groups = planarGroupBounds(order.map((i) => bounds[i]), 4);
      order.forEach((lightIndex, slot) => {
        const { center, u, v } = lightArea(scene.lights[lightIndex])!;
        for (const [, a, b] of points) {
          // A point of the shape (the rectangle's, or the disk's inside the unit circle), as a ray's hit.
          const [sa, sb] = scene.lights[lightIndex].type === 'disk' && a * a + b * b > 1 ? [a / Math.hypot(a, b), b / Math.hypot(a, b)] : [a, b];
          const p = [0, 1, 2].map((k) => center[k] + sa * u[k] + sb * v[k]);
          const inside = (s: Sphere) => Math.hypot(p[0] - s[0], p[1] - s[1], p[2] - s[2]) <= s[3];
          expect(inside(bounds[lightIndex])).toBe(true);
          expect(inside(groups[Math.floor(slot / 4)])).toBe(true);
        }
      });
    }));
  });
});
