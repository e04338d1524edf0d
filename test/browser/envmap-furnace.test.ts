/**
 * The environment furnace: a constant-valued map around a white diffuse
 * sphere renders like the constant environment of the same radiance. The
 * constant sky is found by BSDF sampling alone (every pixel exactly 1); the
 * map is also an emitter of the light interface, sampled from its
 * distribution and combined by MIS, so its image is noisy but must have the
 * same expectation: a sampler whose pdf disagrees with what it draws, a
 * wrong MIS weight or a mis-scaled lookup shows here. Background pixels see
 * the map directly and must equal the constant sky exactly.
 */
import { describe, expect, it } from 'vitest';
import type { LinearImage } from '../../src/node/imageMetrics';
import { decodeEnvironmentMap } from '../../src/scene/envmap';
import { projectSphere } from '../../src/scene/picking';
import type { Scene } from '../../src/scene/types';
import { loadFixtureScene, useRenderSession } from '../support/browser';
import { encodeFlatHdr } from '../support/rgbe';

const SIZE = { width: 64, height: 64 };

describe('environment furnace', () => {
  const session = useRenderSession();

  async function render(scene: Scene, spp: number, files: Record<string, Uint8Array> = {}): Promise<LinearImage> {
    await session().load(scene, { ...SIZE, seed: 5 }, files);
    expect(await session().render(spp)).toBe(spp);
    return { ...SIZE, channels: 4, data: await session().readLinear() };
  }

  it('a constant 8x4 map renders like the constant sky of its radiance; background pixels exactly equal', async () => {
    const file = encodeFlatHdr(8, 4, () => [1, 1, 1]);
    const texel = decodeEnvironmentMap(file, 'one.hdr').rgb[0];
    expect(texel).toBe(1); // 128 * 2^(129 - 136): exact in RGBE
    const base = loadFixtureScene('furnace');
    const constant: Scene = { ...base, environment: { color: [texel, texel, texel], intensity: 0.75 } };
    const mapped: Scene = { ...base, version: 2, environment: { map: 'one.hdr', intensity: 0.75, rotation: 37 } };
    const sky = await render(constant, 16);
    const map = await render(mapped, 64, { 'one.hdr': file });

    const sphere = base.spheres[0];
    const disk = projectSphere(base.camera, 1, sphere.center, sphere.radius)!;
    let background = 0;
    const inside: number[] = [];
    for (let y = 0; y < SIZE.height; y++) {
      for (let x = 0; x < SIZE.width; x++) {
        const p = (y * SIZE.width + x) * 4;
        expect(map.data[p + 3], 'rejected non-finite samples').toBe(0);
        // The constant sky: every sample of every pixel is 0.75 (a convex sphere, white, no light sampling of the sky).
        for (let c = 0; c < 3; c++) expect(Math.abs(sky.data[p + c] - 0.75)).toBeLessThan(1e-4);
        const distance = Math.hypot((x + 0.5) / SIZE.height - disk.u * (SIZE.width / SIZE.height), (y + 0.5) / SIZE.height - disk.v);
        if (distance > disk.radius + 2 / SIZE.height) {
          background++;
          for (let c = 0; c < 3; c++) expect(map.data[p + c], `background pixel ${x},${y}`).toBe(sky.data[p + c]);
        } else if (distance < disk.radius - 2 / SIZE.height) {
          inside.push(map.data[p], map.data[p + 1], map.data[p + 2]);
        }
      }
    }
    expect(background).toBeGreaterThan(1000);
    expect(inside.length / 3).toBeGreaterThan(800);

    // On the sphere every pixel's expectation is 0.75: the spread of the
    // pixels is the noise of one pixel, and their mean must lie within 4
    // standard errors of 0.75 (the channels of a pixel are correlated, so
    // the error counts pixels, not channels).
    const mean = inside.reduce((a, b) => a + b, 0) / inside.length;
    const variance = inside.reduce((a, b) => a + (b - mean) ** 2, 0) / (inside.length - 1);
    const standardError = Math.sqrt(variance / (inside.length / 3));
    console.log(`environment furnace: sphere mean ${mean.toFixed(5)} (sky 0.75), pixel sd ${Math.sqrt(variance).toFixed(4)}, tolerance ${(4 * standardError).toFixed(5)}`);
    expect(variance, 'the map is light-sampled: its image is noisy').toBeGreaterThan(0);
    expect(Math.abs(mean - 0.75)).toBeLessThan(4 * standardError);
    // A gross error cannot hide behind a large noise estimate.
    expect(Math.abs(mean - 0.75)).toBeLessThan(0.01);
  });
});
