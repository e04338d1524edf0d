/**
 * The standard material, as Mitsuba tests a plugin: its sampler (the lobe
 * mixture: GGX visible normals and cosine-weighted Lambert) against its pdf
 * (chi-square on the real GLSL), and its sample weights (f |cos| / pdf)
 * against its directional albedo r + (1 - r) E(mu), E the GGX lobe's albedo
 * from an independent TypeScript quadrature (test/support/ggx.ts). The
 * white and glossy furnaces are in test/browser/furnace.test.ts.
 */
import { describe, expect, it } from 'vitest';
import type { Material, Vec3 } from '../../scene/types';
import { useRenderSession } from '../../../test/support/browser';
import { bsdfWeights, expectSamplerMatchesPdf, samplerChiSquare } from '../../../test/support/bsdfKernels';
import { ggxAlbedo } from '../../../test/support/ggx';

const white = (roughness: number): Material => ({ type: 'standard', color: [1, 1, 1], roughness });
const direction = (theta: number): Vec3 => [Math.sin((theta * Math.PI) / 180), 0, Math.cos((theta * Math.PI) / 180)];

describe('standard material on the GPU', () => {
  const session = useRenderSession();

  for (const { roughness, theta } of [{ roughness: 1, theta: 30 }, { roughness: 0.6, theta: 10 }, { roughness: 0.6, theta: 70 }, { roughness: 0.35, theta: 45 }]) {
    it(`sampler agrees with its pdf (chi-square): roughness ${roughness}, view ${theta} deg`, async () => {
      const result = await samplerChiSquare(session(), white(roughness), direction(theta));
      expectSamplerMatchesPdf(result);
    });
  }

  it('sample weights are f / pdf and average to the albedo r + (1 - r) E(mu)', async () => {
    for (const { roughness, theta } of [{ roughness: 0.3, theta: 20 }, { roughness: 0.7, theta: 60 }]) {
      const ours = await bsdfWeights(session(), white(roughness), direction(theta));
      const albedo = roughness + (1 - roughness) * ggxAlbedo(Math.cos((theta * Math.PI) / 180), roughness * roughness);
      const summary = JSON.stringify({ roughness, theta, ours, albedo });
      expect(ours.worstRatioError, summary).toBeLessThan(1e-4);
      // 5 sigma of the mean, plus the quadrature's 1e-3.
      expect(Math.abs(ours.mean - albedo), summary).toBeLessThan(5 * ours.standardError + 1e-3);
    }
  });
});
