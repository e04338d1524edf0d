/**
 * The denoiser in the headless page (src/denoise on TensorFlow.js WASM):
 * a 16 spp render of the seed scene with Mitsuba guides
 * (test/fixtures/denoise, made by bench/denoise/fixtures.ts) comes out at
 * least 5x closer to the reference, finite, and bit-identical on a second
 * run, without blocking the page's main thread (it runs in a worker); the display of a handed-in linear image is the tracer's own display;
 * bad input gives clear errors; the tracer's own guides have the image's size.
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { decodePfm } from '../../src/image/pfm';
import { relativeMse } from '../../src/node/imageMetrics';
import { FIXTURES, loadFixtureScene, loadReference, renderLinear, useRenderSession } from '../support/browser';

function guide(kind: 'albedo' | 'normal'): Float32Array {
  const pfm = decodePfm(readFileSync(new URL(`denoise/seed-${kind}.pfm`, FIXTURES)));
  const rgba = new Float32Array(pfm.width * pfm.height * 4);
  for (let p = 0; p < pfm.width * pfm.height; p++) rgba.set(pfm.rgb.subarray(p * 3, p * 3 + 3), p * 4);
  return rgba;
}

describe('denoiser', () => {
  const session = useRenderSession();
  const scene = loadFixtureScene('seed');
  const { width, height } = scene.image;
  // The first test's 16 spp render and its denoised error, reused by the tiling test.
  let noisy16: Float32Array | undefined;
  let wholeError = 0;

  it('makes the seed scene at 16 spp at least 5x closer to the reference, finite and deterministic', async () => {
    const noisy = await renderLinear(session(), scene, 16, 1);
    const input = { width, height, color: noisy.data, albedo: guide('albedo'), normal: guide('normal') };
    const first = await session().denoise(input);
    const second = await session().denoise(input);
    expect(first.backend).toBe('wasm');
    // The network runs in a worker: the page's timers keep ticking meanwhile.
    console.log(`main thread: longest gap ${second.longestMainThreadGap.toFixed(0)} ms during a ${second.milliseconds.toFixed(0)} ms denoise`);
    expect(second.longestMainThreadGap).toBeLessThan(second.milliseconds / 3);
    expect(first.data.every(Number.isFinite), 'finite output').toBe(true);
    expect(Buffer.from(second.data.buffer).equals(Buffer.from(first.data.buffer)), 'deterministic').toBe(true);
    const reference = loadReference('seed');
    const before = relativeMse(noisy, reference);
    const after = relativeMse({ width, height, channels: 4, data: first.data }, reference);
    noisy16 = noisy.data;
    wholeError = after;
    console.log(`seed 16 spp: relMSE ${before.toExponential(2)} -> ${after.toExponential(2)} in ${first.milliseconds.toFixed(0)} ms`);
    expect(after * 5).toBeLessThan(before);
  });

  it('denoises in tiles (with OIDN overlaps) about as well as in one piece', async () => {
    if (!noisy16) throw new Error('needs the first test');
    const noisy = { data: noisy16 };
    // Two copies side by side (512x192) in 384-pixel tiles: three tiles with overlaps.
    const twice = (data: Float32Array) => {
      const out = new Float32Array(2 * width * height * 4);
      for (let y = 0; y < height; y++) {
        const row = data.subarray(y * width * 4, (y + 1) * width * 4);
        out.set(row, 2 * y * width * 4);
        out.set(row, (2 * y + 1) * width * 4);
      }
      return out;
    };
    const half = (data: Float32Array, side: 0 | 1) => {
      const out = new Float32Array(width * height * 4);
      for (let y = 0; y < height; y++) out.set(data.subarray((2 * y + side) * width * 4, (2 * y + side + 1) * width * 4), y * width * 4);
      return { width, height, channels: 4, data: out };
    };
    const input = { width: 2 * width, height, color: twice(noisy.data), albedo: twice(guide('albedo')), normal: twice(guide('normal')) };
    const tiled = await session().denoise(input, { maxTileSize: 384 });
    const reference = loadReference('seed');
    for (const side of [0, 1] as const) {
      const error = relativeMse(half(tiled.data, side), reference);
      expect(error / wholeError, `half ${side}: ${error.toExponential(2)} vs ${wholeError.toExponential(2)}`).toBeLessThan(1.25);
    }
  });

  it('displays a handed-in linear image exactly as the tracer displays its own', async () => {
    const linear = await renderLinear(session(), scene, 2, 3, { width: 32, height: 24 });
    for (const tonemap of ['none', 'aces']) {
      const options = { exposure: 0.5, toneMap: tonemap };
      const own = await session().readDisplayed(options);
      const handed = await session().displayLinear(linear.data, 32, 24, options);
      expect(Buffer.from(handed).equals(Buffer.from(own)), tonemap).toBe(true);
    }
  });

  it('names the field of bad input; the tracer hands over guides of the image size', async () => {
    const color = new Float32Array(8 * 6 * 4);
    await expect(session().denoise({ width: 8, height: 6, color, albedo: new Float32Array(10), normal: color })).rejects.toThrow(/albedo: expected 192 values/);
    await expect(session().denoise({ width: 8, height: 5, color, albedo: color, normal: color })).rejects.toThrow(/color: expected/);
    await session().load(scene, { width: 8, height: 6, seed: 0 });
    const guides = await session().readAovs();
    expect(guides.albedo.length).toBe(8 * 6 * 4);
    expect(guides.normal.length).toBe(8 * 6 * 4);
  });
});
