/**
 * A lost WebGL context (WEBGL_lose_context, as a GPU reset or the browser
 * reclaiming a background tab would do): while lost, the PathTracer renders
 * nothing and says why; once restored it rebuilds its programs, textures and
 * targets by itself, and accumulation restarts from zero. Because the random
 * streams are a pure function of (pixel, sample, seed), the image rendered
 * after a restore must be bit-identical to an uninterrupted render.
 */
import { describe, expect, it } from 'vitest';
import type { HeadlessApi } from '../../src/headless/main';
import { parseScene } from '../../src/scene/schema';
import { useRenderSession } from '../support/browser';

const SIZE = { width: 16, height: 12 };
const SPP = 32;
const SEED = 9;

const scene = parseScene({
  camera: { position: [0, 1.5, 5], target: [0, 0.6, 0], fov: 45 },
  environment: { color: [0.5, 0.6, 0.8], intensity: 0.4 },
  ground: { height: 0, material: { color: '#b0b0a8', roughness: 1 } },
  lights: [{ position: [2, 4, 2], radius: 0.6, intensity: 25 }],
  spheres: [
    { center: [-0.8, 0.6, 0], radius: 0.6, material: { color: [0.9, 0.3, 0.2], roughness: 0.6 } },
    { center: [0.8, 0.6, 0], radius: 0.6, material: { color: [0.9, 0.9, 0.9], roughness: 0 } },
  ],
});

type Api = Pick<HeadlessApi, 'loseContext' | 'restoreContext' | 'contextLost'>;

describe('lost WebGL context', () => {
  const session = useRenderSession();
  const pageCall = (method: keyof Api) =>
    session().page.evaluate((m) => (window as unknown as { pathtrace: Api }).pathtrace[m](), method);
  const waitLost = (lost: boolean) =>
    session().page.waitForFunction(
      (want) => (window as unknown as { pathtrace: Api }).pathtrace.contextLost() === want,
      lost,
      { timeout: 10_000 },
    );

  const imageMean = (data: Float32Array) => {
    let sum = 0;
    for (let i = 0; i < data.length; i += 4) sum += data[i] + data[i + 1] + data[i + 2];
    return sum / (data.length / 4) / 3;
  };

  it('stops while lost, rebuilds on restore and accumulates the same image again', async () => {
    const s = session();
    // The uninterrupted render.
    await s.load(scene, { ...SIZE, seed: SEED });
    expect(await s.render(SPP)).toBe(SPP);
    const reference = await s.readLinear();
    expect(imageMean(reference)).toBeGreaterThan(0.05);

    // Lose the context half-way through a second render of the same scene.
    await s.load(scene, { ...SIZE, seed: SEED });
    expect(await s.render(SPP / 2)).toBe(SPP / 2);
    await pageCall('loseContext');
    await waitLost(true);
    // While lost: nothing accumulates, and reading says why instead of returning garbage.
    expect(await s.render(8)).toBe(0);
    await expect(s.readLinear()).rejects.toThrow(/context is lost/);

    await pageCall('restoreContext');
    await waitLost(false);
    // Accumulation restarts from zero after the restore, then goes on normally.
    expect(await s.render(SPP / 2)).toBe(SPP / 2);
    expect(await s.render(SPP / 2)).toBe(SPP);
    const restored = await s.readLinear();

    // Same seed, same sample indices: the same bits as the uninterrupted render.
    let worst = 0;
    for (let i = 0; i < reference.length; i++) worst = Math.max(worst, Math.abs(restored[i] - reference[i]));
    expect(worst, 'max abs difference to the uninterrupted render').toBeLessThan(1e-6);
    expect(Math.abs(imageMean(restored) / imageMean(reference) - 1)).toBeLessThan(1e-6);
    for (let p = 0; p < SIZE.width * SIZE.height; p++) expect(restored[p * 4 + 3], 'rejected samples').toBe(0);
  });

  it('survives repeated losses, and a loss before any sample', async () => {
    const s = session();
    await s.load(scene, { ...SIZE, seed: SEED });
    for (let round = 0; round < 3; round++) {
      await pageCall('loseContext');
      await waitLost(true);
      await pageCall('restoreContext');
      await waitLost(false);
    }
    expect(await s.render(SPP)).toBe(SPP);
    const after = await s.readLinear();
    await s.load(scene, { ...SIZE, seed: SEED });
    await s.render(SPP);
    const fresh = await s.readLinear();
    expect(Math.abs(imageMean(after) / imageMean(fresh) - 1)).toBeLessThan(1e-6);
    // The displayed image works too (the display pass was rebuilt as well).
    const displayed = await s.readDisplayed({ exposure: 0, toneMap: 'none' });
    expect(displayed.some((v, i) => i % 4 !== 3 && v > 0)).toBe(true);
  });

  it('a loaded scene after a loss renders normally (a fresh tracer, a fresh context)', async () => {
    const s = session();
    await s.load(scene, { ...SIZE, seed: SEED });
    await pageCall('loseContext');
    await waitLost(true);
    await s.load(scene, { ...SIZE, seed: SEED });
    expect(await s.render(SPP)).toBe(SPP);
    expect(imageMean(await s.readLinear())).toBeGreaterThan(0.05);
  });
});
