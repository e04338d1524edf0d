/**
 * Textured emission (scene format version 3: a principled emission's color
 * may be a texture): seen by BSDF sampling and sampled by next-event
 * estimation, with MIS between them (lights/mesh_emitter.glsl: triangles
 * picked by their texture's power, the area density in the MIS weights).
 *
 * A Lambertian ground (albedo 0.8) under a huge emissive quad facing down
 * (2000 x 2000 units, 1 unit above, the checker repeated 400 times along
 * each side, so the emission is uniform at every scale the ground sees):
 * the ground's radiance is albedo x the quad's mean radiance, the mean of
 * the texture's sRGB-decoded texels times the intensity (the filtered
 * texture averages to the texels' mean over whole periods). The quad
 * reflects almost nothing (black base color, ior 1.01: Fresnel 2.5e-5).
 * Measured (opaque): 0.5635 against 0.5634 at 256 spp. The quad is half
 * see-through (opacity 0.5): its emission counts where it is opaque, so
 * the ground gets half (light sampling multiplied by the opacity; a
 * BSDF-sampled ray passes through with probability 0.5); the light the
 * ground sends up passes through or meets the black quad.
 */
import { readFileSync } from 'node:fs';
import { decode } from 'fast-png';
import { describe, expect, it } from 'vitest';
import { srgbToLinear } from '../../src/scene/color';
import { parseScene } from '../../src/scene/schema';
import { renderLinear, useRenderSession } from '../support/browser';

const INTENSITY = 2;
/** A see-through emitter: its emission is seen where it is opaque, o * Le (by light sampling too). */
const OPACITY = 0.5;
const ALBEDO = 0.8;
const scene = (color: unknown) =>
  parseScene({
    version: 3,
    image: { width: 24, height: 24 },
    camera: { position: [0, 0.5, 0], target: [0, 0, 0.0001], up: [0, 0, 1], fov: 40 },
    environment: null,
    ground: { material: { color: [ALBEDO, ALBEDO, ALBEDO], roughness: 1 } },
    meshes: [
      {
        file: '../meshes/uvquad.obj',
        position: [0, 1, 0],
        scale: 1000,
        material: { type: 'principled', baseColor: [0, 0, 0], ior: 1.01, roughness: 1, opacity: OPACITY, emission: { color, intensity: INTENSITY } },
      },
    ],
  });

function checkerMean(): number[] {
  const png = decode(readFileSync(new URL('../fixtures/textures/checker.png', import.meta.url)));
  const mean = [0, 0, 0];
  const n = png.width * png.height;
  for (let i = 0; i < n; i++) for (let c = 0; c < 3; c++) mean[c] += srgbToLinear(png.data[i * png.channels + c] / 255) / n;
  return mean;
}

describe('textured emission', () => {
  const session = useRenderSession();

  it("lights a ground with the texture's mean radiance, through light sampling and BSDF sampling", async () => {
    const image = await renderLinear(session(), scene({ image: '../textures/checker.png', uv: { scale: [400, 400] } }), 256, 1);
    const mean = checkerMean();
    // The mean over pixels and its standard error (pixels are independent).
    for (let c = 0; c < 3; c++) {
      const values = Array.from({ length: image.width * image.height }, (_, p) => image.data[p * image.channels + c]);
      const m = values.reduce((a, b) => a + b, 0) / values.length;
      const se = Math.sqrt(values.reduce((a, v) => a + (v - m) ** 2, 0) / (values.length - 1) / values.length);
      const expected = ALBEDO * INTENSITY * OPACITY * mean[c];
      expect(Math.abs(m - expected), `channel ${c}: ${m} vs ${expected} (se ${se})`).toBeLessThan(5 * se + 1e-3 * expected);
      // Not vacuous: an emission 3% off would be seen (measured se 0.58% at
      // 128 spp: the pass-throughs add noise).
      expect(5 * se).toBeLessThan(0.03 * expected);
    }
  });
});
