/**
 * A sample drawn in tiles (render/tiles.ts) gives the same bits as a sample
 * drawn over the whole image at once: the fragment shaders address pixels
 * by gl_FragCoord only, and each pixel adds its samples in order, so neither
 * the tiling nor the split of the work into draws and calls may change a
 * single float. Checked against untiled renders of the same seed: tiled by
 * a small pathsPerDraw (render), by irregular renderPaths calls mixing parts
 * of samples and whole ones (as the page's loop does), and with the guide
 * buffers kept along; the version-1 fixtures tiled against their stored
 * renders. A sample counts only when all its tiles are drawn: the mean read
 * back never mixes n and n + 1 samples.
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { decodePfm } from '../../src/image/pfm';
import type { LoadOptions } from '../../src/headless/main';
import type { Scene } from '../../src/scene/types';
import { FIXTURES, loadFixtureScene, useRenderSession } from '../support/browser';
import { random } from '../support/random';
import { V1_RENDER, V1_SCENES } from '../../scripts/make-v1-renders';

const same = (a: Float32Array, b: Float32Array) => Buffer.from(a.buffer, a.byteOffset, a.byteLength).equals(Buffer.from(b.buffer, b.byteOffset, b.byteLength));

function firstDifference(a: Float32Array, b: Float32Array): string {
  let count = 0;
  let first = '';
  for (let i = 0; i < a.length; i++) {
    if (Object.is(a[i], b[i])) continue;
    if (count++ === 0) first = `float ${i}: ${a[i]} vs ${b[i]}`;
  }
  return `${count} of ${a.length} floats differ; first ${first}`;
}

describe('tiled draws', () => {
  const session = useRenderSession();
  const page = () => session().page;
  // Odd sizes: tiles at the right edge are narrower, the last row of tiles one pixel high.
  const size = { width: 157, height: 95 };
  const pixels = size.width * size.height;
  const SPP = 5;

  /** Untiled: every sample in one full-screen draw. */
  async function untiled(scene: Scene, options: LoadOptions, spp: number): Promise<void> {
    await session().load(scene, options);
    await page().evaluate((n) => window.pathtrace.render(n, n, 1e12), spp);
  }

  /** Renders `spp` samples by renderPaths calls of the sizes `next()` gives, never past `spp`. */
  async function byPaths(scene: Scene, options: LoadOptions, spp: number, next: () => number): Promise<number> {
    await session().load(scene, options);
    let calls = 0;
    for (;;) {
      const state = await page().evaluate(() => window.pathtrace.renderPaths(0));
      const left = (spp - state.sampleCount - state.sampleProgress) * pixels;
      if (left < 1) break;
      const before = state.sampleCount;
      const after = await page().evaluate((paths) => window.pathtrace.renderPaths(paths), Math.min(left, next()));
      expect(after.sampleCount).toBeGreaterThanOrEqual(before);
      expect(after.traced).toBeGreaterThan(0);
      calls++;
    }
    expect(await page().evaluate(() => window.pathtrace.renderPaths(0).sampleCount)).toBe(spp);
    return calls;
  }

  it('gives the bits of untiled draws, whatever the tiles and calls', async () => {
    const scene = loadFixtureScene('seed');
    const options = { ...size, seed: 7 };
    await untiled(scene, options, SPP);
    const whole = await session().readLinear();

    // render() with draws of at most 700 paths: about 3 tiles each.
    await session().load(scene, options);
    await page().evaluate((n) => window.pathtrace.render(n, n, 700), SPP);
    const smallDraws = await session().readLinear();
    expect(same(smallDraws, whole), firstDifference(smallDraws, whole)).toBe(true);

    // renderPaths: parts of a sample and several samples in one call, mixed.
    const rand = random(3);
    const calls = await byPaths(scene, options, SPP, () => (rand() < 0.2 ? pixels * (1 + 2 * rand()) : 50 + rand() * pixels * 0.4));
    expect(calls).toBeGreaterThan(SPP);
    const irregular = await session().readLinear();
    expect(same(irregular, whole), firstDifference(irregular, whole)).toBe(true);
    expect(whole.some((v) => v > 0)).toBe(true);
  });

  it('keeps the guide buffers along, with the bits of untiled draws', async () => {
    const scene = loadFixtureScene('glossy');
    const options = { ...size, seed: 2, aovs: true };
    await untiled(scene, options, 3);
    const whole = await session().readAovs();
    const rand = random(5);
    await byPaths(scene, options, 3, () => 100 + rand() * pixels * 0.3);
    const tiled = await session().readAovs();
    expect(tiled.samples).toBe(3);
    expect(whole.samples).toBe(3);
    expect(same(tiled.albedo, whole.albedo), firstDifference(tiled.albedo, whole.albedo)).toBe(true);
    expect(same(tiled.normal, whole.normal), firstDifference(tiled.normal, whole.normal)).toBe(true);
  });

  it('counts a sample only when all its tiles are drawn', async () => {
    const scene = loadFixtureScene('seed');
    await session().load(scene, { ...size, seed: 4 });
    // The first sample, part way: nothing counts yet; the display shows the tiles drawn so far.
    let state = await page().evaluate((n) => window.pathtrace.renderPaths(n), pixels * 0.4);
    expect(state.sampleCount).toBe(0);
    expect(state.sampleProgress).toBeGreaterThan(0.3);
    expect(state.sampleProgress).toBeLessThan(0.5);
    expect((await session().readLinear()).every((v) => v === 0)).toBe(true);
    const preview = await session().readDisplayed({ exposure: 0, toneMap: 'none' });
    const lit = (rgba: Uint8Array) => {
      let n = 0;
      for (let p = 0; p < rgba.length; p += 4) if (rgba[p] + rgba[p + 1] + rgba[p + 2] > 0) n++;
      return n;
    };
    expect(lit(preview) / pixels).toBeGreaterThan(0.25);
    expect(lit(preview) / pixels).toBeLessThan(0.5);
    // Two whole samples, then part of a third: what is read and shown is the mean of two.
    state = await page().evaluate((n) => window.pathtrace.renderPaths(n), pixels * 1.6);
    expect(state.sampleCount).toBe(2);
    expect(state.sampleProgress).toBe(0);
    const two = await session().readLinear();
    const twoShown = await session().readDisplayed({ exposure: 0, toneMap: 'aces' });
    state = await page().evaluate((n) => window.pathtrace.renderPaths(n), pixels * 0.7);
    expect(state.sampleCount).toBe(2);
    expect(state.sampleProgress).toBeGreaterThan(0.6);
    expect(same(await session().readLinear(), two)).toBe(true);
    expect(Buffer.from(await session().readDisplayed({ exposure: 0, toneMap: 'aces' })).equals(Buffer.from(twoShown))).toBe(true);
    // render() finishes the sample in progress as one of its samples.
    expect((await page().evaluate(() => window.pathtrace.render(2, 2))).sampleCount).toBe(4);
    const tiled = await session().readLinear();
    await untiled(scene, { ...size, seed: 4 }, 4);
    expect(same(tiled, await session().readLinear())).toBe(true);
  });

  for (const name of V1_SCENES) {
    it(`renders the version-1 scene ${name} in tiles bit-identically to its fixture`, async () => {
      const { width, height, spp, seed } = V1_RENDER;
      const old = decodePfm(readFileSync(new URL(`v1-renders/${name}.pfm`, FIXTURES)));
      await session().load(loadFixtureScene(name), { width, height, seed });
      // Draws of at most 200 paths: a sample of 64x48 in 16 draws.
      await page().evaluate((n) => window.pathtrace.render(n, n, 200), spp);
      const now = await session().readLinear();
      const rgb = new Float32Array(width * height * 3);
      for (let p = 0; p < width * height; p++) for (let c = 0; c < 3; c++) rgb[p * 3 + c] = now[p * 4 + c];
      expect(same(rgb, old.rgb), firstDifference(rgb, old.rgb)).toBe(true);
    });
  }
});
