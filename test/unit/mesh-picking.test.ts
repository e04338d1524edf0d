import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { fitMesh, frameCamera, looksZUp, worldBoundingSphere } from '../../src/app/meshFit';
import { vertexNormals } from '../../src/app/meshControls';
import { cameraRay } from '../../src/scene/camera';
import { transformMesh } from '../../src/scene/mesh';
import { intersectMesh, meshBounds, pickObject, projectPoint } from '../../src/scene/picking';
import { defaultScene } from '../../src/scene/presets';
import type { Mesh, TriangleMesh, Vec3 } from '../../src/scene/types';
import { icosphere } from '../support/icosphere';

const ico = icosphere(2, false);
const placed = (over: Partial<Mesh> = {}): Mesh => ({
  file: 'ico.obj', material: { type: 'standard', color: [1, 1, 1], roughness: 1 },
  position: [0, 1, 0], rotation: [0, 0, 0], scale: [1, 1, 1], ...over,
});
const ray = (origin: Vec3, direction: Vec3) => {
  const n = Math.hypot(...direction);
  return { origin, direction: direction.map((d) => d / n) as Vec3 };
};

/** Brute force in world space: every transformed triangle, Moller-Trumbore, two-sided. */
function worldHit(r: { origin: Vec3; direction: Vec3 }, mesh: Mesh, data: TriangleMesh): number | null {
  const w = transformMesh(data, mesh);
  let best: number | null = null;
  for (let i = 0; i < w.indices.length; i += 3) {
    const [a, b, c] = [0, 1, 2].map((k) => [...w.positions.subarray(w.indices[i + k] * 3, w.indices[i + k] * 3 + 3)]);
    const e1 = b.map((v, k) => v - a[k]), e2 = c.map((v, k) => v - a[k]);
    const d = r.direction, s = r.origin.map((v, k) => v - a[k]);
    const cross = (x: number[], y: number[]) => [x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]];
    const dot = (x: number[], y: number[]) => x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
    const p = cross([...d], e2), det = dot(e1, p);
    if (Math.abs(det) < 1e-14) continue;
    const u = dot(s, p) / det, q = cross(s, e1), v = dot([...d], q) / det, t = dot(e2, q) / det;
    if (u >= 0 && v >= 0 && u + v <= 1 && t > 1e-6 && (best === null || t < best)) best = t;
  }
  return best;
}

describe('mesh picking', () => {
  it('hits a placed icosphere at its near surface, and misses beside it', () => {
    const mesh = placed({ position: [0, 1, 0], scale: [0.5, 0.5, 0.5] });
    const t = intersectMesh(ray([0, 1, 5], [0, 0, -1]), mesh, ico)!;
    expect(t).toBeGreaterThan(4.5 - 0.02);
    expect(t).toBeLessThan(4.5 + 1e-9);
    expect(intersectMesh(ray([0, 1.6, 5], [0, 0, -1]), mesh, ico)).toBeNull();
    expect(intersectMesh(ray([0, 1, 5], [0, 0, 1]), mesh, ico)).toBeNull();
  });

  it('agrees with a world-space brute force under random transforms and rays', () => {
    const v = fc.double({ min: -2, max: 2, noNaN: true });
    fc.assert(fc.property(
      fc.tuple(v, v, v), fc.tuple(fc.double({ min: -180, max: 180, noNaN: true }), fc.double({ min: -180, max: 180, noNaN: true }), fc.double({ min: -180, max: 180, noNaN: true })),
      fc.tuple(fc.double({ min: 0.2, max: 3, noNaN: true }), fc.double({ min: 0.2, max: 3, noNaN: true }), fc.double({ min: 0.2, max: 3, noNaN: true })),
      fc.tuple(v, v, v),
      (position, rotation, scale, aim) => {
        const mesh = placed({ position: position as Vec3, rotation: rotation as Vec3, scale: scale as Vec3 });
        const origin: Vec3 = [6, 5, 7];
        const r = ray(origin, [aim[0] - origin[0] + position[0], aim[1] - origin[1] + position[1], aim[2] - origin[2] + position[2]]);
        const got = intersectMesh(r, mesh, ico);
        const want = worldHit(r, mesh, ico);
        if (want === null || got === null) return (want === null) === (got === null) || Math.abs((want ?? got)! - (got ?? want)!) < 1e-6;
        return Math.abs(got - want) < 1e-4 * want;
      },
    ), { numRuns: 150 });
  });

  it('pickObject returns the mesh in front of a sphere, and nothing without its data', () => {
    const scene = defaultScene();
    scene.spheres = [{ center: [0, 1, -3], radius: 0.5, material: { type: 'standard', color: [1, 1, 1], roughness: 1 } }];
    scene.meshes = [placed({ position: [0, 1, 0] })];
    const r = ray([0, 1, 5], [0, 0, -1]);
    expect(pickObject(scene, r, () => ico)).toMatchObject({ kind: 'mesh', index: 0 });
    expect(pickObject(scene, r, () => undefined)).toMatchObject({ kind: 'sphere', index: 0 });
    expect(pickObject(scene, r)).toMatchObject({ kind: 'sphere' });
  });
});

describe('fitting an added model', () => {
  const zUp: TriangleMesh = { ...ico, positions: ico.positions.map((p, i) => (i % 3 === 2 ? p * 3 + 3 : p * 0.7)) };

  it('turns a model tall along z upright, but never a glTF file', () => {
    expect(looksZUp(zUp, 'statue.obj')).toBe(true);
    expect(looksZUp(zUp, 'statue.glb')).toBe(false);
    expect(looksZUp(ico, 'ball.ply')).toBe(false);
    expect(fitMesh(zUp, 'statue.obj', defaultScene()).rotation).toEqual([-90, 0, 0]);
  });

  it('stands the model on the ground under the target, sized to the view, and frames it', () => {
    const scene = defaultScene();
    for (const [data, name] of [[zUp, 'statue.obj'], [ico, 'ball.ply']] as const) {
      const fit = fitMesh(data, name, scene);
      const mesh = placed(fit);
      const world = transformMesh(data, mesh);
      const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
      for (let i = 0; i < world.positions.length; i++) {
        min[i % 3] = Math.min(min[i % 3], world.positions[i]);
        max[i % 3] = Math.max(max[i % 3], world.positions[i]);
      }
      expect(min[1]).toBeCloseTo(scene.ground!.height, 5);
      expect((min[0] + max[0]) / 2).toBeCloseTo(scene.camera.target[0], 5);
      expect((min[2] + max[2]) / 2).toBeCloseTo(scene.camera.target[2], 5);
      const size = Math.max(...max.map((m, k) => m - min[k]));
      const view = Math.hypot(...scene.camera.target.map((t, k) => t - scene.camera.position[k]));
      expect(size / view).toBeCloseTo(0.3, 5);
      if (name === 'statue.obj') expect(max[1] - min[1]).toBeCloseTo(size, 5);
      // Every vertex projects inside the image after framing.
      const bounds = worldBoundingSphere(mesh, data);
      const camera = frameCamera(scene.camera, bounds.center, bounds.radius, 4 / 3);
      for (let i = 0; i < world.positions.length; i += 3) {
        const p = projectPoint(camera, 4 / 3, [world.positions[i], world.positions[i + 1], world.positions[i + 2]])!;
        expect(p.u).toBeGreaterThan(0); expect(p.u).toBeLessThan(1);
        expect(p.v).toBeGreaterThan(0); expect(p.v).toBeLessThan(1);
      }
      // The framed camera's central ray hits the model.
      expect(intersectMesh(cameraRay(camera, 4 / 3, 0.5, 0.5), mesh, data)).not.toBeNull();
    }
  });

  it('bounds and smooth normals of the bundled bunny are sane', async () => {
    const { default: bunny } = await import('bunny');
    const positions = Float32Array.from(bunny.positions.flat());
    const indices = Uint32Array.from(bunny.cells.flat());
    const normals = vertexNormals(positions, indices);
    const { min, max } = meshBounds({ positions, indices, normals });
    expect(max[1] - min[1]).toBeGreaterThan(9);
    let outward = 0;
    const c = [0, 1, 2].map((k) => (min[k] + max[k]) / 2);
    for (let v = 0; v < positions.length; v += 3) {
      expect(Math.hypot(normals[v], normals[v + 1], normals[v + 2])).toBeCloseTo(1, 4);
      outward += [0, 1, 2].reduce((s, k) => s + normals[v + k] * (positions[v + k] - c[k]), 0) > 0 ? 1 : 0;
    }
    expect(outward / (positions.length / 3)).toBeGreaterThan(0.8);
  });
});
