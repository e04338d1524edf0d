/**
 * The denoiser's guide buffers (PathTracer.readAovs): albedo and normal of
 * the first non-specular hit, following ideal mirrors and smooth glass, the
 * sky's clamped radiance with a zero normal (Open Image Denoise's
 * conventions; issue 12).
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { decodePfm } from '../../src/image/pfm';
import { parseScene } from '../../src/scene/schema';
import type { Scene } from '../../src/scene/types';
import { FIXTURES, fixtureFiles, loadFixtureScene, useRenderSession } from '../support/browser';

interface Guides { albedo: Float32Array; normal: Float32Array; samples: number; width: number; height: number }

const SIZE = { width: 33, height: 25 };

/** A pixel's RGB (rows top to bottom). */
function pixel(data: Float32Array, width: number, x: number, y: number): number[] {
  const i = (y * width + x) * 4;
  return [data[i], data[i + 1], data[i + 2]];
}

function expectClose(actual: number[], expected: number[], tolerance: number, what: string): void {
  for (let c = 0; c < 3; c++) expect(Math.abs(actual[c] - expected[c]), `${what}: ${actual} vs ${expected}`).toBeLessThanOrEqual(tolerance);
}

/** Every value finite, nothing rejected, albedo in [0, 1], normals no longer than 1. */
function expectWellFormed(g: Guides, what: string): void {
  for (let p = 0; p < g.width * g.height; p++) {
    const a = pixel(g.albedo, g.width, p % g.width, Math.floor(p / g.width));
    const n = pixel(g.normal, g.width, p % g.width, Math.floor(p / g.width));
    for (const v of [...a, ...n]) expect(Number.isFinite(v), `${what}: pixel ${p} finite`).toBe(true);
    for (const v of a) expect(v >= 0 && v <= 1, `${what}: pixel ${p} albedo ${a} in [0, 1]`).toBe(true);
    expect(Math.hypot(n[0], n[1], n[2]), `${what}: pixel ${p} normal ${n}`).toBeLessThan(1 + 1e-5);
    expect(g.albedo[p * 4 + 3], `${what}: rejected albedo samples`).toBe(0);
    expect(g.normal[p * 4 + 3], `${what}: rejected normal samples`).toBe(0);
  }
}

function scene(json: object): Scene {
  return parseScene({ version: 2, image: SIZE, ...json });
}

describe('AOV guide buffers', () => {
  const session = useRenderSession();

  async function guides(s: Scene, spp: number, options: { seed?: number; aovs?: boolean } = {}): Promise<Guides> {
    await session().load(s, { ...s.image, seed: options.seed ?? 1, aovs: options.aovs }, fixtureFiles(s));
    if (spp > 0) await session().render(spp);
    const g = { ...(await session().readAovs()), ...s.image };
    expectWellFormed(g, 'guides');
    return g;
  }

  it('a flat white diffuse plane: albedo exactly 1 and normal exactly (0, 1, 0) at every pixel', async () => {
    const plane = scene({
      camera: { position: [0, 2, 0], target: [0, 0, -1], fov: 20 },
      environment: { color: [0.2, 0.3, 0.4], intensity: 1 },
      ground: { height: 0, material: { color: [1, 1, 1], roughness: 1 } },
    });
    for (const spp of [0, 3, 40]) {
      const g = await guides(plane, spp);
      expect(g.samples).toBe(Math.min(16, Math.max(1, spp)));
      for (let p = 0; p < SIZE.width * SIZE.height; p++) {
        expect(pixel(g.albedo, SIZE.width, p % SIZE.width, Math.floor(p / SIZE.width))).toEqual([1, 1, 1]);
        expect(pixel(g.normal, SIZE.width, p % SIZE.width, Math.floor(p / SIZE.width))).toEqual([0, 1, 0]);
      }
    }
  });

  it('the sky: its radiance clamped to [0, 1] as albedo and a zero normal; a light: its clamped radiance and its normal', async () => {
    const sky = scene({
      camera: { position: [0, 0, 0], target: [0, 0, -1], fov: 30 },
      environment: { color: [0.5, 2, 0.25], intensity: 1 },
      ground: null,
      lights: [{ position: [0, 0, -10], radius: 1, color: [1, 0.5, 0.25], intensity: 1.6 }],
    });
    const g = await guides(sky, 16);
    const cx = (SIZE.width - 1) / 2;
    const cy = (SIZE.height - 1) / 2;
    // The corner sees the sky; the light covers the centre (1 / 10 rad > a pixel).
    expect(pixel(g.albedo, SIZE.width, 0, 0)).toEqual([0.5, 1, 0.25]);
    expect(pixel(g.normal, SIZE.width, 0, 0)).toEqual([0, 0, 0]);
    expectClose(pixel(g.albedo, SIZE.width, cx, cy), [1, 0.8, 0.4], 1e-6, 'light albedo');
    // The pixel's rays spread over ~0.2 rad of the light's surface; the mean tilts a little.
    expectClose(pixel(g.normal, SIZE.width, cx, cy), [0, 0, 1], 0.05, 'light normal');
  });

  it('a mirror sphere shows the red diffuse sphere it reflects, tinted by the mirror; its own normal is not used', async () => {
    const red = [0.8, 0.1, 0.1];
    const mirrorScene = (mirror: number[]) =>
      scene({
        camera: { position: [0, 0, 5], target: [0, 0, 0], fov: 10 },
        environment: null,
        ground: null,
        spheres: [
          { center: [0, 0, 0], radius: 1, material: { color: mirror, roughness: 0 } },
          // Behind the camera: the mirror's centre reflects it straight back.
          { center: [0, 0, 40], radius: 20, material: { color: red, roughness: 1 } },
        ],
      });
    const cx = (SIZE.width - 1) / 2;
    const cy = (SIZE.height - 1) / 2;
    const white = await guides(mirrorScene([1, 1, 1]), 16);
    expectClose(pixel(white.albedo, SIZE.width, cx, cy), red, 1e-6, 'through a white mirror');
    // The red sphere's normal where the reflected ray meets it faces -z (the
    // mirror's is +z); the pixel's rays spread over ~0.04 rad of it.
    expectClose(pixel(white.normal, SIZE.width, cx, cy), [0, 0, -1], 0.05, 'normal through the mirror');
    const tinted = await guides(mirrorScene([0.5, 1, 0.25]), 16);
    expectClose(pixel(tinted.albedo, SIZE.width, cx, cy), [0.4, 0.1, 0.025], 1e-6, 'through a tinted mirror');
    // A rough sphere of the same color is its own first non-specular hit.
    const rough = scene({ ...mirrorScene([1, 1, 1]), spheres: [{ center: [0, 0, 0], radius: 1, material: { color: [0.3, 0.6, 0.9], roughness: 0.5 } }] });
    const own = await guides(rough, 16);
    expectClose(pixel(own.albedo, SIZE.width, cx, cy), [0.3, 0.6, 0.9], 1e-6, 'rough sphere');
    expectClose(pixel(own.normal, SIZE.width, cx, cy), [0, 0, 1], 0.02, 'rough sphere normal');
  });

  it('smooth glass in front of a red wall shows the red wall (Fresnel-weighted); rough glass shows itself', async () => {
    const red = [0.8, 0.1, 0.1];
    const glass = (roughness: number) =>
      scene({
        camera: { position: [0, 0, 5], target: [0, 0, 0], fov: 10 },
        environment: null,
        ground: null,
        spheres: [
          { center: [0, 0, 0], radius: 1, material: { type: 'dielectric', color: [1, 1, 1], roughness, ior: 1.5 } },
          // The wall: its surface at z = -10, facing the camera.
          { center: [0, 0, -40], radius: 30, material: { color: red, roughness: 1 } },
        ],
      });
    const cx = (SIZE.width - 1) / 2;
    const cy = (SIZE.height - 1) / 2;
    const smooth = await guides(glass(0), 16);
    // Near normal incidence a sample refracts twice with probability ~0.92
    // and ends on the wall; reflected samples escape to the black sky (0).
    // So the albedo is k * red and the normal k * (0, 0, 1), 0.5 < k <= 1.
    let k = 0;
    for (let dy = -1; dy <= 1; dy++) {
      for (let dx = -1; dx <= 1; dx++) {
        const a = pixel(smooth.albedo, SIZE.width, cx + dx, cy + dy);
        const n = pixel(smooth.normal, SIZE.width, cx + dx, cy + dy);
        const ka = a[0] / red[0];
        expectClose(a, red.map((c) => c * ka), 1e-5, 'red through glass');
        expectClose(n, [0, 0, ka], 0.02, 'wall normal through glass');
        k += ka / 9;
      }
    }
    expect(k).toBeGreaterThan(0.5);
    const rough = await guides(glass(0.5), 16);
    expectClose(pixel(rough.albedo, SIZE.width, cx, cy), [1, 1, 1], 1e-6, 'rough glass is its own albedo');
    expectClose(pixel(rough.normal, SIZE.width, cx, cy), [0, 0, 1], 1e-2, 'rough glass normal');
  });

  it('the seed scene matches the guides Mitsuba 3 computes with the same conventions (bench/denoise/guides.py)', async () => {
    const seed = loadFixtureScene('seed');
    const { width, height } = seed.image;
    const g = await guides(seed, 16);
    for (const kind of ['albedo', 'normal'] as const) {
      // RGB, rows top to bottom (decodePfm flips PFM's bottom-up rows).
      const reference = decodePfm(readFileSync(new URL(`denoise/seed-${kind}.pfm`, FIXTURES)));
      expect([reference.width, reference.height]).toEqual([width, height]);
      // Measured: mean |d| 0.0005 (albedo), 0.001 (normal); worst 16x16 block mean 0.003, 0.005
      // (edges differ by sampling alone: 16 jittered samples here, 64 there).
      const block = 16;
      const blocks = new Float64Array(Math.ceil(width / block) * Math.ceil(height / block) * 3);
      let total = 0;
      for (let y = 0; y < height; y++) {
        for (let x = 0; x < width; x++) {
          for (let c = 0; c < 3; c++) {
            const d = g[kind][(y * width + x) * 4 + c] - reference.rgb[(y * width + x) * 3 + c];
            total += Math.abs(d);
            blocks[((Math.floor(y / block) * Math.ceil(width / block)) + Math.floor(x / block)) * 3 + c] += d / (block * block);
          }
        }
      }
      expect(total / (width * height * 3), `${kind}: mean |difference|`).toBeLessThan(0.003);
      expect(Math.max(...blocks.map(Math.abs)), `${kind}: worst block mean difference`).toBeLessThan(0.02);
    }
  });

  it('every shared scene gives finite, well-formed guides; keeping them while rendering gives the same bits and leaves the colour unchanged', async () => {
    const small = { width: 48, height: 36 };
    for (const name of ['seed', 'mirrors', 'glass', 'emissive', 'emissive-mesh', 'envmap', 'bunny']) {
      const s = { ...loadFixtureScene(name), image: small };
      const lazy = await guides(s, 6, { seed: 3 });
      let nonZero = 0;
      for (let p = 0; p < small.width * small.height; p++) nonZero += lazy.albedo[p * 4] + lazy.albedo[p * 4 + 1] + lazy.albedo[p * 4 + 2] > 0 ? 1 : 0;
      expect(nonZero, `${name}: albedo not blank`).toBeGreaterThan(0);
      if (name === 'seed') {
        // Rows run top to bottom: the top row sees the sky, the bottom row the ground.
        expectClose(pixel(lazy.normal, small.width, 0, 0), [0, 0, 0], 0, 'seed: sky normal, top left');
        expectClose(pixel(lazy.albedo, small.width, 0, 0), [0.55 * 0.35, 0.7 * 0.35, 0.35], 1e-6, 'seed: sky albedo');
        expectClose(pixel(lazy.normal, small.width, 24, small.height - 1), [0, 1, 0], 0, 'seed: ground normal, bottom');
        expectClose(pixel(lazy.albedo, small.width, 24, small.height - 1), [0.75, 0.75, 0.72], 1e-6, 'seed: ground albedo');
      }
      const colourWithout = await session().readLinear();
      const kept = await guides(s, 6, { seed: 3, aovs: true });
      const colourWith = await session().readLinear();
      expect(kept.samples, name).toBe(6);
      expect(Buffer.from(kept.albedo.buffer).equals(Buffer.from(lazy.albedo.buffer)), `${name}: albedo bits`).toBe(true);
      expect(Buffer.from(kept.normal.buffer).equals(Buffer.from(lazy.normal.buffer)), `${name}: normal bits`).toBe(true);
      expect(Buffer.from(colourWith.buffer).equals(Buffer.from(colourWithout.buffer)), `${name}: colour bits`).toBe(true);
    }
  });
});
