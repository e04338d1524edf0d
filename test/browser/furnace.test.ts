/**
 * The white furnace: a white Lambertian sphere under a uniform white sky
 * reflects exactly what it receives, so every pixel's expected value is 1.
 * A path tracer that loses or gains energy anywhere (BSDF weights, sampling,
 * Russian roulette, the accumulation) shows it here.
 */
import { describe, expect, it } from 'vitest';
import { blockMeans, meanValue } from '../../src/node/imageMetrics';
import { cameraRay } from '../../src/scene/camera';
import type { Scene, Vec3 } from '../../src/scene/types';
import { loadFixtureScene, renderLinear, useRenderSession } from '../support/browser';
import { ggxAlbedo } from '../support/ggx';

describe('white furnace', () => {
  const session = useRenderSession();

  it('renders 1.0: image mean within 0.3%, every 8x8 block within 2%', async () => {
    const scene = loadFixtureScene('furnace');
    const image = await renderLinear(session(), scene, 16, 7);
    expect(Math.abs(meanValue(image) - 1)).toBeLessThan(0.003);
    const { means } = blockMeans(image, 8);
    for (const m of means) expect(Math.abs(m - 1)).toBeLessThan(0.02);
    // Stronger than the issue asks, and what the physics says: no sample is
    // lost, so every pixel is 1 up to float rounding.
    for (let p = 0; p < image.width * image.height; p++) {
      expect(Math.abs(image.data[p * 4] - 1)).toBeLessThan(1e-4);
      expect(image.data[p * 4 + 3], 'rejected non-finite samples').toBe(0);
    }
  });

  it('a glossy white sphere reflects exactly the GGX albedo (the glossy furnace)', async () => {
    // Single-scattering GGX loses the energy of rays that would scatter
    // between microfacets; the model does not restore it. So a white sphere
    // of roughness r under a white sky has the expected pixel value
    // r + (1 - r) E(mu), E the lobe's directional albedo at the viewing
    // angle (a reflected ray leaves a convex sphere for good). E comes from
    // an independent TypeScript quadrature; the expected image is
    // supersampled 4x4 per pixel with the camera rays of src/scene/camera.ts.
    const base = loadFixtureScene('furnace');
    const size = { width: 64, height: 64 };
    const spp = 64;
    for (const roughness of [0.02, 0.3, 0.7]) {
      const scene = {
        ...base,
        spheres: [{ ...base.spheres[0], material: { type: 'standard' as const, color: [1, 1, 1] as [number, number, number], roughness } }],
      };
      const image = await renderLinear(session(), scene, spp, 3, size);
      const expected = expectedFurnaceImage(scene, size.width, size.height);
      // Samples lie in [0, ~1.2]: sigma per sample < 0.6, so the image mean's
      // sigma < 0.6 / sqrt(64 * 64 * 64) = 1.2e-3 and an 8x8 block's < 9.4e-3;
      // we allow 4 sigma.
      const actualMean = meanValue(image);
      const expectedMean = expected.reduce((a, b) => a + b, 0) / expected.length;
      expect(Math.abs(actualMean - expectedMean), `roughness ${roughness}: ${actualMean} vs ${expectedMean}`).toBeLessThan(0.005);
      const actualBlocks = blockMeans(image, 8).means;
      const expectedBlocks = blockMeans({ ...size, channels: 1, data: Float32Array.from(expected) }, 8, 1).means;
      for (let b = 0; b < expectedBlocks.length; b++) {
        expect(Math.abs(actualBlocks[b * 3] - expectedBlocks[b]), `roughness ${roughness}, block ${b}`).toBeLessThan(0.038);
      }
      console.log(`glossy furnace r=${roughness}: mean ${actualMean.toFixed(5)}, expected ${expectedMean.toFixed(5)}`);
      if (roughness < 0.0316) expect(Math.abs(actualMean - 1)).toBeLessThan(1e-4); // an ideal mirror loses nothing
    }
  });
});

/** Per-pixel expectation (rows top to bottom) of the furnace scene with one white sphere. */
function expectedFurnaceImage(scene: Scene, width: number, height: number): number[] {
  const sphere = scene.spheres[0];
  const roughness = sphere.material.roughness as number;
  const alpha = roughness * roughness;
  const table = Array.from({ length: 65 }, (_, i) => (alpha < 1e-3 ? 1 : ggxAlbedo(Math.max(1e-4, i / 64), alpha)));
  const albedo = (mu: number) => {
    const x = mu * 64;
    const i = Math.min(63, Math.floor(x));
    return table[i] + (table[i + 1] - table[i]) * (x - i);
  };
  const out: number[] = [];
  const sub = 4;
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      let sum = 0;
      for (let j = 0; j < sub; j++) {
        for (let i = 0; i < sub; i++) {
          const ray = cameraRay(scene.camera, width / height, (x + (i + 0.5) / sub) / width, (y + (j + 0.5) / sub) / height);
          const mu = sphereCosine(ray.origin, ray.direction, sphere.center, sphere.radius);
          sum += mu === null ? 1 : roughness + (1 - roughness) * albedo(mu);
        }
      }
      out.push(sum / (sub * sub));
    }
  }
  return out;
}

/** cos(angle between the viewer and the normal) where the ray first hits the sphere, or null. */
function sphereCosine(o: Vec3, d: Vec3, c: Vec3, r: number): number | null {
  const oc = [o[0] - c[0], o[1] - c[1], o[2] - c[2]];
  const b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
  const disc = b * b - (oc[0] ** 2 + oc[1] ** 2 + oc[2] ** 2 - r * r);
  if (disc < 0) return null;
  const t = -b - Math.sqrt(disc);
  if (t <= 0) return null;
  const n = [0, 1, 2].map((k) => (o[k] + t * d[k] - c[k]) / r);
  return Math.max(0, -(n[0] * d[0] + n[1] * d[1] + n[2] * d[2]));
}
