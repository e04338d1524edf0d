/**
 * The watertight furnace: a closed icosphere mesh of a white Lambertian
 * material under a uniform white sky reflects exactly what it receives, so
 * every pixel's expected value is 1. A ray that slips through a crack
 * between two triangles enters the closed (two-sided) mesh, bounces inside
 * and loses energy: a dark speck. So every pixel is checked, not the mean,
 * with a tolerance derived from the measured noise of independent batches.
 * A control renders the same sphere with one visible triangle removed: the
 * check must flag it (the test can fail).
 */
import { describe, expect, it } from 'vitest';
import type { RenderSession } from '../../src/node/session';
import type { Material, Scene } from '../../src/scene/types';
import { loadFixtureScene, useRenderSession } from '../support/browser';
import { icosphere } from '../support/icosphere';
import { groupMeshes } from '../../src/render/bvh/groups';
import type { TriangleMesh } from '../../src/scene/types';

const SIZE = { width: 80, height: 80 };
const BATCHES = 3;
const SPP = 8;

function toObj(mesh: TriangleMesh, skip: (triangle: number) => boolean = () => false): Uint8Array {
  const lines: string[] = [];
  for (let i = 0; i < mesh.positions.length; i += 3) lines.push(`v ${mesh.positions[i]} ${mesh.positions[i + 1]} ${mesh.positions[i + 2]}`);
  for (let t = 0; t < mesh.indices.length / 3; t++) {
    if (!skip(t)) lines.push(`f ${mesh.indices[t * 3] + 1} ${mesh.indices[t * 3 + 1] + 1} ${mesh.indices[t * 3 + 2] + 1}`);
  }
  return new TextEncoder().encode(lines.join('\n') + '\n');
}

function furnaceScene(file: string, instanced = false): Scene {
  const base = loadFixtureScene('furnace');
  const material: Material = { type: 'standard', color: [1, 1, 1], roughness: 1 };
  return {
    ...base,
    version: 2,
    image: SIZE,
    spheres: [],
    // Rotated and scaled off the axes, so edges cross pixels at every angle.
    meshes: [
      { file, material, position: [0.05, -0.03, 0], rotation: [17, 33, 5], scale: [1.1, 1.1, 1.1] },
      // Two more meshes of the same file: with a file big enough, three instances of one stored copy (src/render/bvh/groups.ts).
      ...(instanced
        ? ([
            { file, material, position: [1, 1, 0.3], rotation: [-40, 10, 70], scale: [0.25, 0.3, 0.2] },
            { file, material, position: [-1.05, -1, 0.2], rotation: [5, -60, 20], scale: [0.2, 0.15, 0.22] },
          ] satisfies Scene['meshes'])
        : []),
    ],
  };
}

interface FurnaceCheck {
  /** Pixels whose mean is off 1 by more than the tolerance. */
  specks: number;
  worst: number;
  tolerance: number;
  mean: number;
}

/** Renders BATCHES independent batches; the tolerance is 6 sigma of a pixel's mean (pooled over the image) plus float rounding. */
async function checkFurnace(session: RenderSession, scene: Scene, bytes: Uint8Array): Promise<FurnaceCheck> {
  const pixels = SIZE.width * SIZE.height;
  const batches: Float32Array[] = [];
  for (let b = 0; b < BATCHES; b++) {
    await session.load(scene, { ...SIZE, seed: 100 + b }, { [scene.meshes[0].file]: bytes });
    expect(await session.render(SPP)).toBe(SPP);
    batches.push(await session.readLinear());
  }
  const means = new Float64Array(pixels);
  let pooledVariance = 0;
  for (let p = 0; p < pixels; p++) {
    const values = batches.map((data) => (data[p * 4] + data[p * 4 + 1] + data[p * 4 + 2]) / 3);
    const m = values.reduce((a, v) => a + v, 0) / BATCHES;
    means[p] = m;
    pooledVariance += values.reduce((a, v) => a + (v - m) ** 2, 0) / (BATCHES - 1) / pixels;
  }
  const tolerance = 1e-4 + 6 * Math.sqrt(pooledVariance / BATCHES);
  let specks = 0;
  let worst = 0;
  for (let p = 0; p < pixels; p++) {
    const error = Math.abs(means[p] - 1);
    worst = Math.max(worst, error);
    if (error > tolerance) specks++;
  }
  return { specks, worst, tolerance, mean: means.reduce((a, v) => a + v, 0) / pixels };
}

describe('watertight furnace', () => {
  const session = useRenderSession();
  const sphere = icosphere(3, false);

  it('a closed white icosphere in a white furnace is 1 in every pixel', async () => {
    const result = await checkFurnace(session(), furnaceScene('ico.obj'), toObj(sphere));
    console.log(`mesh furnace: mean ${result.mean.toFixed(6)}, worst pixel off by ${result.worst.toExponential(2)}, tolerance ${result.tolerance.toExponential(2)}`);
    expect(result.specks).toBe(0);
    expect(Math.abs(result.mean - 1)).toBeLessThan(1e-3);
  }, 120_000);

  it('three instances of one stored icosphere are 1 in every pixel', async () => {
    const dense = icosphere(6, false); // 81920 triangles: big enough to be instanced, not copied
    const scene = furnaceScene('ico6.obj', true);
    expect(groupMeshes(scene, () => dense.indices.length / 3).shared).toEqual([[0, 1, 2]]);
    const result = await checkFurnace(session(), scene, toObj(dense));
    console.log(`instanced furnace: mean ${result.mean.toFixed(6)}, worst pixel off by ${result.worst.toExponential(2)}, tolerance ${result.tolerance.toExponential(2)}`);
    expect(result.specks).toBe(0);
    expect(Math.abs(result.mean - 1)).toBeLessThan(1e-3);
  }, 120_000);

  it('the check finds a hole: the same sphere missing one triangle facing the camera', async () => {
    // The triangle whose centroid points most toward the camera (+z, before the mesh's small rotation).
    let front = 0;
    let best = -Infinity;
    for (let t = 0; t < sphere.indices.length / 3; t++) {
      const z = [0, 1, 2].reduce((s, k) => s + sphere.positions[sphere.indices[t * 3 + k] * 3 + 2], 0);
      if (z > best) [best, front] = [z, t];
    }
    const result = await checkFurnace(session(), furnaceScene('holed.obj'), toObj(sphere, (t) => t === front));
    console.log(`holed furnace: ${result.specks} specks, worst ${result.worst.toFixed(3)}`);
    expect(result.specks).toBeGreaterThan(5);
  }, 120_000);
});
