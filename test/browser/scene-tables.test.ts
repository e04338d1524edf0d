/**
 * The scene tables run on over several 2048-texel rows of the data texture
 * (src/render/layout/scene.ts). A scene with more materials and spheres than
 * one row holds renders each sphere where it is and in its own colour: the
 * visible ones are chosen so that their sphere records and materials lie past
 * the first row, one of them straddling a row boundary. If sceneData ignored
 * the row (or the upload only sent row 0), these spheres would be read from
 * other records or from zeros and would be missing or wrongly coloured.
 */
import { describe, expect, it } from 'vitest';
import { MATERIAL, SCENE_ROW_TEXELS, SECTIONS, SPHERE } from '../../src/render/layout/scene';
import { MAX_SPHERES } from '../../src/scene/limits';
import { parseScene } from '../../src/scene/schema';
import type { Vec3 } from '../../src/scene/types';
import { renderLinear, useRenderSession } from '../support/browser';

const row = (texel: number) => Math.floor(texel / SCENE_ROW_TEXELS);
const sphereTexel = (i: number) => SECTIONS.spheres + i * SPHERE.texels;
const materialTexel = (i: number) => SECTIONS.materials + i * MATERIAL.texels;
/** Whether a record of `texels` texels from `first` has texels in two rows. */
const straddles = (first: number, texels: number) => row(first) !== row(first + texels - 1);

describe('scene tables over several rows', () => {
  const session = useRenderSession();

  it('renders spheres whose records and materials lie past the first row, each in its own colour', async () => {
    // Sphere i has material i (no ground, no meshes, no lights). Enough
    // spheres that the material table alone runs past the first row.
    const firstInRow1 = Math.ceil(SCENE_ROW_TEXELS / MATERIAL.texels);
    const count = firstInRow1 + 16;
    expect(count).toBeLessThanOrEqual(MAX_SPHERES);
    // The material that holds the first texel of row 1 (straddling rows 0
    // and 1 when MATERIAL is not a power-of-two size), a sphere record that
    // straddles two rows if the layout has one, and the last sphere.
    const materialAcross = Math.floor(SCENE_ROW_TEXELS / MATERIAL.texels);
    const across = Array.from({ length: count }, (_, i) => i).find((i) => straddles(sphereTexel(i), SPHERE.texels)) ?? count - 2;
    const visible = [materialAcross, across, firstInRow1 + 3, count - 1];
    expect(new Set(visible).size).toBe(visible.length);
    for (const i of visible) expect(row(sphereTexel(i)), `sphere ${i}'s record`).toBeGreaterThanOrEqual(1);
    expect(row(materialTexel(materialAcross + 1) - 1), 'material reaching into row 1').toBeGreaterThanOrEqual(1);
    expect(row(materialTexel(count - 1))).toBeGreaterThanOrEqual(1);

    const colors: Vec3[] = [[0.9, 0.1, 0.1], [0.1, 0.8, 0.2], [0.15, 0.25, 0.9], [0.85, 0.75, 0.1]];
    const xs = [-2.4, -0.8, 0.8, 2.4];
    // The others: tiny, far behind the camera, each with its own grey, so
    // each shows up in no pixel and in no reflected ray to speak of.
    const spheres = Array.from({ length: count }, (_, i) => {
      const slot = visible.indexOf(i);
      if (slot >= 0) return { center: [xs[slot], 0, 0], radius: 0.5, material: { color: colors[slot], roughness: 1 } };
      return { center: [(i % 32) * 10 - 160, Math.floor(i / 32) * 10 - 160, 1000], radius: 1e-3, material: { color: [(i % 10) / 10, (i % 10) / 10, (i % 10) / 10], roughness: 1 } };
    });
    const size = { width: 96, height: 48 };
    const fov = 40;
    const distance = 5;
    const scene = parseScene({
      camera: { position: [0, 0, distance], target: [0, 0, 0], fov },
      image: size,
      render: { maxBounces: 4 },
      environment: { color: [1, 1, 1], intensity: 1 },
      spheres,
    });

    const image = await renderLinear(session(), scene, 32, 1, size);
    // A white-sky furnace: a Lambertian sphere reflects its colour, less what
    // its neighbours hide of the sky. The mean over 6x6 pixels around its
    // centre (32 spp each) is within 0.05 of it (measured: at most 0.03
    // off, the outer spheres); the colours differ by 0.6 or more, and a
    // record read from the wrong texel would give another sphere or none.
    const halfWidth = distance * Math.tan((fov * Math.PI) / 360) * (size.width / size.height);
    visible.forEach((index, slot) => {
      const cx = Math.floor(((xs[slot] / halfWidth + 1) / 2) * size.width);
      const cy = size.height / 2;
      const sum = [0, 0, 0];
      let pixels = 0;
      for (let y = cy - 3; y < cy + 3; y++) {
        for (let x = cx - 3; x < cx + 3; x++) {
          const at = (y * size.width + x) * 4;
          for (let c = 0; c < 3; c++) sum[c] += image.data[at + c];
          expect(image.data[at + 3], 'rejected samples').toBe(0);
          pixels++;
        }
      }
      const mean = sum.map((v) => v / pixels);
      const message = `sphere ${index} (record at texel ${sphereTexel(index)}, material at ${materialTexel(index)}), pixels around ${cx},${cy}: ${mean.map((v) => v.toFixed(4))}`;
      mean.forEach((v, c) => expect(Math.abs(v - colors[slot][c]), message).toBeLessThan(0.05));
    });
  });
});
