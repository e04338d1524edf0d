/**
 * glTF vertex colors render as the format says (baseColor =
 * baseColorFactor x COLOR_0): a quad facing the camera whose COLOR_0 runs
 * from red at x = -1 to green at x = +1 (white baseColorFactor, principled,
 * metallic 0, roughness 1) under a constant white sky, direct light only.
 *
 * Principled's sampling and its weights but the diffuse lobe's do not depend
 * on baseColor (lobe probabilities, the specular lobe with specTint 0), so
 * with the same seed the renders follow the same paths and each channel is
 * exactly d * baseColor + s per pixel: the quad with baseColorFactor white
 * (W = d + s) and black (K = s), both without COLOR_0, give per pixel the
 * base color the COLOR_0 render (A) saw, (A - K) / (W - K), free of noise.
 * It must be the interpolated COLOR_0 at the pixel's point: ((1 - x) / 2,
 * (1 + x) / 2, 0), x from the pinhole projection of the pixel's centre (the
 * box filter's samples average to it: the colour is affine in x across the
 * pixel). The colored quad is rendered four ways, smooth or flat, with or
 * without texture coordinates (each a layout of the BVH's attribute block:
 * pack.ts; the flat quad shades as the smooth one, its vertex normals being
 * its face's, so W and K serve all four), and instanced (a 100k-triangle
 * grid of the same quad named by two meshes, stored once: groups.ts).
 */
import { describe, expect, it } from 'vitest';
import { groupMeshes, trianglesIn } from '../../src/render/bvh/groups';
import { loadSceneAssets } from '../../src/scene/assets';
import { resolveFileMaterials } from '../../src/scene/fileMaterials';
import { parseScene } from '../../src/scene/schema';
import { useRenderSession } from '../support/browser';
import { colorQuadGlb } from '../support/colorQuad';

const SIZE = { width: 24, height: 24 };
const SPP = 8;
const FOV = 40;
const DISTANCE = 3;

const scene = (meshes: unknown[] = [{ file: 'quad.glb' }]) =>
  parseScene({
    version: 3,
    image: SIZE,
    camera: { position: [0, 0, DISTANCE], target: [0, 0, 0], fov: FOV },
    render: { maxBounces: 1 },
    environment: { color: [1, 1, 1], intensity: 1 },
    meshes,
  });

/** x on the plane z = 0 seen through pixel column i's centre (square image, camera on +z looking at the origin). */
const pixelX = (i: number) => DISTANCE * Math.tan((FOV * Math.PI) / 360) * ((2 * (i + 0.5)) / SIZE.width - 1);

describe('vertex colors (glTF COLOR_0)', () => {
  const session = useRenderSession();

  async function render(glb: Uint8Array, meshes?: unknown[]): Promise<Float32Array> {
    await session().load(scene(meshes), { ...SIZE, seed: 3 }, { 'quad.glb': glb });
    expect(await session().render(SPP)).toBe(SPP);
    return session().readLinear();
  }

  let references: Promise<{ white: Float32Array; black: Float32Array }> | undefined;
  /** W and K: the quad without COLOR_0, baseColorFactor white and black. */
  const whiteAndBlack = () =>
    (references ??= (async () => ({
      white: await render(await colorQuadGlb({ colors: false, baseColorFactor: [1, 1, 1] })),
      black: await render(await colorQuadGlb({ colors: false, baseColorFactor: [0, 0, 0] })),
    }))());

  /** Checks the base color recovered from `colored` at every pixel inside the quad against COLOR_0 interpolated there. */
  async function expectInterpolatedColors(colored: Float32Array, label: string): Promise<void> {
    const { white, black } = await whiteAndBlack();
    let checked = 0;
    let worst = 0;
    for (let row = 0; row < SIZE.height; row++) {
      for (let i = 0; i < SIZE.width; i++) {
        const x = pixelX(i);
        const y = -pixelX(row); // rows top to bottom
        // Pixels whose footprint lies inside the quad (a pixel is 0.09 wide here).
        if (Math.max(Math.abs(x), Math.abs(y)) > 0.9) continue;
        const p = (row * SIZE.width + i) * 4;
        const expected = [(1 - x) / 2, (1 + x) / 2, 0];
        for (let c = 0; c < 3; c++) {
          const diffuse = white[p + c] - black[p + c];
          expect(diffuse, `pixel (${i}, ${row}): the diffuse part is there`).toBeGreaterThan(0.1);
          const seen = (colored[p + c] - black[p + c]) / diffuse;
          worst = Math.max(worst, Math.abs(seen - expected[c]));
          expect(seen, `${label}: pixel (${i}, ${row}) channel ${c}`).toBeCloseTo(expected[c], 1);
        }
        checked++;
      }
    }
    console.log(`vertex colors, ${label}: ${checked} pixels, largest error of the recovered base color ${worst.toExponential(2)}`);
    expect(checked).toBeGreaterThan(200);
    // The pixel-centre value, to the box filter's jitter (8 samples over a pixel spanning 0.045 in colour).
    expect(worst).toBeLessThan(0.02);
  }

  it('the quad renders its interpolated vertex colors times the base color factor, smooth or flat, with or without uvs', async () => {
    for (const layout of [{ flat: false, uvs: false }, { flat: false, uvs: true }, { flat: true, uvs: false }, { flat: true, uvs: true }]) {
      await expectInterpolatedColors(await render(await colorQuadGlb({ colors: true, baseColorFactor: [1, 1, 1], ...layout })), JSON.stringify(layout));
    }
  });

  it('an instanced colored file renders its vertex colors too', async () => {
    const glb = await colorQuadGlb({ colors: true, baseColorFactor: [1, 1, 1], grid: 224 });
    // The second instance lies behind the quad, hidden by it and below its hemisphere of light.
    const meshes = [{ file: 'quad.glb' }, { file: 'quad.glb', position: [0, 0, -5] }];
    const { scene: resolved, assets } = resolveFileMaterials(scene(meshes), await loadSceneAssets(scene(meshes), async () => glb));
    expect(groupMeshes(resolved, trianglesIn(assets)).shared, 'the file is instanced').toEqual([[0, 1]]);
    await expectInterpolatedColors(await render(glb, meshes), 'instanced 224 x 224 grid');
  });
});
