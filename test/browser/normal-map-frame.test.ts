/**
 * The normal map's tangent frame on a mirrored chart (scene format "Meshes
 * in version 3": glTF's rule, the bitangent up the image, toward decreasing
 * v, whichever way u runs). A flat quad in the xz plane, its image's "up"
 * toward -z, under a small light low on the -z side; a constant normal map
 * with green > 0.5 tilts the normal ~31 degrees up the image, toward the
 * light, so the quad is brighter than with a flat map. The quad's chart is
 * unmirrored (u along +x) or mirrored (u along -x), v the same in both: both
 * must tilt toward -z. That the mirrored chart is mirrored shows with red
 * > 0.5 under a light on the +x side: x follows u, so red tilts the normal
 * toward the light on the unmirrored chart and away from it on the mirrored
 * one.
 *
 * Mitsuba's own frame (y = cross(n, dp/du), no sign) agrees on the unmirrored
 * chart and turns the tilt over on the mirrored one, toward +z and away from
 * the light. Dropping the sign on the mirrored chart is exactly the same as
 * keeping it and inverting green (byte 255 - g gives 2 g' - 1 = -(2 g - 1),
 * and the rest of the adapter sees only the perturbed normal), so the render
 * of the mirrored chart with green inverted is what the shader would render
 * without the sign: the test shows it dark, so its "brighter than flat"
 * assertion on the mirrored chart is one that would fail.
 */
import { encode } from 'fast-png';
import { describe, expect, it } from 'vitest';
import { parseScene } from '../../src/scene/schema';
import { useRenderSession } from '../support/browser';

const SIZE = { width: 32, height: 32 };
const SPP = 8;

/**
 * The quad y = 0, |x|, |z| <= 1, two triangles facing +y. `vt` is OBJ's (v
 * up from the bottom, turned over on loading: v' = 1 - vt), so v' = (z + 1)
 * / 2 and the image's top row (v' = 0) lies at z = -1.
 */
function quadObj(mirrored: boolean): Uint8Array {
  const corners = [[-1, 1], [1, 1], [1, -1], [-1, -1]];
  const lines = corners.map(([x, z]) => `v ${x} 0 ${z}`);
  for (const [x, z] of corners) lines.push(`vt ${mirrored ? (1 - x) / 2 : (x + 1) / 2} ${(1 - z) / 2}`);
  lines.push('f 1/1 2/2 3/3', 'f 1/1 3/3 4/4');
  return new TextEncoder().encode(lines.join('\n') + '\n');
}

/** A 4 x 4 constant RGB image, 8-bit, read as stored (a normal map). */
function constantPng(rgb: [number, number, number]): Uint8Array {
  const data = new Uint8Array(4 * 4 * 4).map((_, i) => (i % 4 === 3 ? 255 : rgb[i % 4]));
  return encode({ width: 4, height: 4, data, channels: 4, depth: 8 });
}

const MAPS = {
  flat: constantPng([128, 128, 255]),
  /** (0.5, 0.8, 1.0): up the image. */
  up: constantPng([128, 204, 255]),
  /** Green inverted: what the mirrored chart renders without the bitangent's sign. */
  down: constantPng([128, 255 - 204, 255]),
  /** (0.8, 0.5, 1.0): along increasing u. */
  alongU: constantPng([204, 128, 255]),
};

/** From the quad's centre each light is 18 degrees above the horizon. */
const LIGHTS = { minusZ: [0, 0.8, -2.5], plusX: [2.5, 0.8, 0] } as const;

function scene(map: keyof typeof MAPS, light: keyof typeof LIGHTS) {
  return parseScene({
    version: 3,
    image: SIZE,
    camera: { position: [0, 3, 2], target: [0, 0, 0], fov: 45 },
    render: { maxBounces: 1 },
    lights: [{ position: [...LIGHTS[light]], radius: 0.2, intensity: 60 }],
    meshes: [{ file: 'quad.obj', material: { type: 'principled', baseColor: [0.8, 0.8, 0.8], roughness: 1, normalMap: { image: `${map}.png` } } }],
  });
}

describe('normal map frame on a mirrored chart', () => {
  const session = useRenderSession();

  /** Mean luminance-ish (RGB mean) of the image: the background is black and the light is out of view. */
  async function meanRadiance(mirrored: boolean, map: keyof typeof MAPS, light: keyof typeof LIGHTS = 'minusZ'): Promise<number> {
    const files = { 'quad.obj': quadObj(mirrored), [`${map}.png`]: MAPS[map] };
    await session().load(scene(map, light), { ...SIZE, seed: 7 }, files);
    expect(await session().render(SPP)).toBe(SPP);
    const rgba = await session().readLinear();
    let sum = 0;
    for (let p = 0; p < SIZE.width * SIZE.height; p++) {
      for (let c = 0; c < 3; c++) {
        expect(Number.isFinite(rgba[p * 4 + c])).toBe(true);
        sum += rgba[p * 4 + c];
      }
    }
    return sum / (3 * SIZE.width * SIZE.height);
  }

  it('green tilts the normal up the image on both charts; without the bitangent sign the mirrored chart would tilt it down', async () => {
    const flat = await meanRadiance(false, 'flat');
    const flatMirrored = await meanRadiance(true, 'flat');
    const unmirrored = await meanRadiance(false, 'up');
    const mirrored = await meanRadiance(true, 'up');
    const signDropped = await meanRadiance(true, 'down');
    const ratios = { flatMirrored: flatMirrored / flat, unmirrored: unmirrored / flat, mirrored: mirrored / flat, signDropped: signDropped / flat };
    console.log(`normal map frame: flat ${flat.toFixed(5)}, relative to it ${JSON.stringify(ratios, (_, v) => (typeof v === 'number' ? Number(v.toFixed(4)) : v))}`);
    expect(flat).toBeGreaterThan(0);
    // Tilted toward the light, cos(41 deg) against the flat quad's cos(72 deg): ~2.4 times at the centre.
    expect(ratios.unmirrored).toBeGreaterThan(1.5);
    expect(ratios.mirrored).toBeGreaterThan(1.5);
    // Tilted away (toward +z), the light is below the perturbed normal's hemisphere over most of the quad.
    expect(ratios.signDropped).toBeLessThan(0.5);
    // Both charts turn the normal the same way: the same image but for red's 128 (0.0039, not 0: a
    // 0.2-degree tilt along +-x, which the mirror turns over), with the same random numbers.
    expect(Math.abs(ratios.flatMirrored - 1)).toBeLessThan(0.02);
    expect(Math.abs(mirrored / unmirrored - 1)).toBeLessThan(0.02);

    // The mirrored chart is mirrored: red tilts along u, which runs along -x there.
    const flatPlusX = await meanRadiance(false, 'flat', 'plusX');
    const alongU = { unmirrored: (await meanRadiance(false, 'alongU', 'plusX')) / flatPlusX, mirrored: (await meanRadiance(true, 'alongU', 'plusX')) / flatPlusX };
    console.log(`normal map frame, red under a light on +x, relative to flat: ${JSON.stringify(alongU, (_, v) => (typeof v === 'number' ? Number(v.toFixed(4)) : v))}`);
    expect(alongU.unmirrored).toBeGreaterThan(1.5);
    expect(alongU.mirrored).toBeLessThan(0.5);
  });
});
