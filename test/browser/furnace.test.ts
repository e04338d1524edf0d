/**
 * The white furnace: a white Lambertian sphere under a uniform white sky
 * reflects exactly what it receives, so every pixel's expected value is 1.
 * A path tracer that loses or gains energy anywhere (BSDF weights, sampling,
 * Russian roulette, the accumulation) shows it here.
 */
import { describe, expect, it } from 'vitest';
import { blockMeans, meanValue } from '../../src/node/imageMetrics';
import { loadFixtureScene, renderLinear, useRenderSession } from '../support/browser';

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

  it('stays 1.0 for glossy and mirror white spheres and a white ground', async () => {
    const base = loadFixtureScene('furnace');
    for (const roughness of [0, 0.02, 0.3, 0.7]) {
      const scene = {
        ...base,
        spheres: [{ ...base.spheres[0], material: { color: [1, 1, 1] as [number, number, number], roughness } }],
      };
      const image = await renderLinear(session(), scene, 16, 3, { width: 64, height: 64 });
      // GGX with separable Smith G loses energy to multiple scattering that
      // it does not model (up to a few % at alpha ~0.5); the pure mirror and
      // the diffuse part do not. So the mean stays within the lobe's loss.
      const tolerance = roughness === 0 ? 1e-4 : 0.03;
      expect(Math.abs(meanValue(image) - 1), `roughness ${roughness}`).toBeLessThan(tolerance);
    }
  });
});
