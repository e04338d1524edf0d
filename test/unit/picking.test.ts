import { describe, expect, it } from 'vitest';
import { cameraRay } from '../../src/scene/camera';
import {
  intersectPlaneY,
  intersectSphere,
  pickAt,
  pickObject,
  pickSurface,
  projectPoint,
  projectSphere,
} from '../../src/scene/picking';
import { defaultScene } from '../../src/scene/presets';
import type { Scene, Vec3 } from '../../src/scene/types';

const aspect = 256 / 192;

describe('ray intersections', () => {
  it('hits a sphere in front at the near surface, from inside at the exit', () => {
    const ray = { origin: [0, 0, 5] as [number, number, number], direction: [0, 0, -1] as [number, number, number] };
    expect(intersectSphere(ray, [0, 0, 0], 1)).toBeCloseTo(4, 12);
    expect(intersectSphere({ ...ray, origin: [0, 0, 0] }, [0, 0, 0], 1)).toBeCloseTo(1, 12);
    expect(intersectSphere(ray, [0, 2, 0], 1)).toBeNull();
    expect(intersectSphere({ ...ray, direction: [0, 0, 1] }, [0, 0, 0], 1)).toBeNull();
  });

  it('hits a horizontal plane only in front', () => {
    const down = { origin: [0, 2, 0] as [number, number, number], direction: [0, -1, 0] as [number, number, number] };
    expect(intersectPlaneY(down, 0)).toBeCloseTo(2, 12);
    expect(intersectPlaneY({ ...down, direction: [0, 1, 0] }, 0)).toBeNull();
    expect(intersectPlaneY({ ...down, direction: [1, 0, 0] }, 0)).toBeNull();
  });
});

describe('picking the default scene', () => {
  const scene = defaultScene();

  it('picks every sphere and the light through its projected centre', () => {
    scene.spheres.forEach((sphere, index) => {
      const p = projectPoint(scene.camera, aspect, sphere.center)!;
      expect(pickAt(scene, aspect, p.u, p.v)).toMatchObject({ kind: 'sphere', index });
    });
    const light = projectPoint(scene.camera, aspect, (scene.lights[0] as { position: Vec3 }).position)!;
    expect(pickAt(scene, aspect, light.u, light.v)).toMatchObject({ kind: 'light', index: 0 });
  });

  it('projects onto the same pixel that cameraRay goes through', () => {
    const ray = cameraRay(scene.camera, aspect, 0.3, 0.7);
    const point = ray.direction.map((d, i) => ray.origin[i] + 4 * d) as [number, number, number];
    const p = projectPoint(scene.camera, aspect, point)!;
    expect(p.u).toBeCloseTo(0.3, 6); // gl-matrix works in float32
    expect(p.v).toBeCloseTo(0.7, 6);
  });

  it('returns nothing for the sky and the ground, and the ground for focusing', () => {
    expect(pickAt(scene, aspect, 0.02, 0.02)).toBeNull();
    expect(pickAt(scene, aspect, 0.02, 0.98)).toBeNull();
    const ground = pickSurface(scene, cameraRay(scene.camera, aspect, 0.02, 0.98));
    expect(ground?.kind).toBe('ground');
    expect(ground!.point[1]).toBeCloseTo(0, 9);
  });

  it('picks the nearer of two overlapping spheres', () => {
    const two: Scene = {
      ...scene,
      spheres: [
        { center: [0, 1, -3], radius: 1, material: scene.spheres[0].material },
        { center: [0, 1, 2], radius: 0.5, material: scene.spheres[0].material },
      ],
      lights: [],
    };
    const ray = { origin: [0, 1, 10] as [number, number, number], direction: [0, 0, -1] as [number, number, number] };
    expect(pickObject(two, ray)).toMatchObject({ kind: 'sphere', index: 1, t: 7.5 });
  });

  it('hides objects below the ground plane', () => {
    const buried: Scene = { ...scene, spheres: [{ ...scene.spheres[0], center: [0, -3, 0] }], lights: [] };
    const p = projectPoint(buried.camera, aspect, [0, -3, 0])!;
    expect(pickAt(buried, aspect, p.u, p.v)).toBeNull();
  });

  it('projects a sphere outline whose radius matches the silhouette edge', () => {
    const sphere = scene.spheres[1];
    const outline = projectSphere(scene.camera, aspect, sphere.center, sphere.radius)!;
    // Just inside the outline's top edge hits, just outside misses (to a few %).
    expect(pickAt(scene, aspect, outline.u, outline.v - outline.radius * 0.95)).toMatchObject({ index: 1 });
    const outside = pickAt(scene, aspect, outline.u, outline.v - outline.radius * 1.08);
    expect(outside?.index === 1 && outside.kind === 'sphere').toBe(false);
  });

  it('returns null for points behind the camera', () => {
    expect(projectPoint(scene.camera, aspect, [0, 2.2, 20])).toBeNull();
  });
});
