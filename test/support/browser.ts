/**
 * Shared set-up of the browser tests: one headless Chromium per test file,
 * which must really have WebGL2 with float render targets (a machine that
 * silently has none must fail here, not pass).
 */
import { readFileSync } from 'node:fs';
import { afterAll, beforeAll, expect } from 'vitest';
import { openRenderSession, type RenderSession } from '../../src/node/session';
import { parseSceneText } from '../../src/scene/schema';
import type { Scene } from '../../src/scene/types';
import { assetReferences } from '../../src/scene/assets';
import type { LinearImage } from '../../src/node/imageMetrics';
import { decodePfm } from '../../src/image/pfm';

export const FIXTURES = new URL('../fixtures/', import.meta.url);

export function useRenderSession(): () => RenderSession {
  let session: RenderSession | undefined;
  beforeAll(async () => {
    session = await openRenderSession();
    const probe = await session.probe();
    expect(probe.webgl2, 'WebGL2 context').toBe(true);
    expect(probe.floatTargets, 'EXT_color_buffer_float').toBe(true);
  });
  afterAll(async () => {
    await session?.close();
  });
  return () => {
    if (!session) throw new Error('browser session failed to open');
    return session;
  };
}

export function loadFixtureScene(name: string): Scene {
  return parseSceneText(readFileSync(new URL(`scenes/${name}.json`, FIXTURES), 'utf8'));
}

/** The bytes of the files a fixture scene names, read relative to test/fixtures/scenes/ as the format says. */
export function fixtureFiles(scene: Scene): Record<string, Uint8Array> {
  return Object.fromEntries(
    assetReferences(scene).map((ref) => [ref.file, new Uint8Array(readFileSync(new URL(ref.file, new URL('scenes/', FIXTURES))))]),
  );
}

export function loadReference(name: string): LinearImage {
  const pfm = decodePfm(readFileSync(new URL(`references/${name}.pfm`, FIXTURES)));
  return { width: pfm.width, height: pfm.height, channels: 3, data: pfm.rgb };
}

/** Renders `spp` samples per pixel and returns the linear image; asserts it is not blank. */
export async function renderLinear(
  session: RenderSession,
  scene: Scene,
  spp: number,
  seed: number,
  size: { width: number; height: number } = scene.image,
  adaptive = false,
): Promise<LinearImage> {
  await session.load(scene, { ...size, seed, adaptive }, fixtureFiles(scene));
  if (adaptive) {
    // Rounds that double, as the command line's growing chunks: each one
    // re-estimates the noise (PathTracerOptions.adaptive).
    let count = 0;
    for (let round = 4; count < spp; round *= 2) count = await session.render(Math.min(round, spp - count));
    expect(Math.abs(count - spp)).toBeLessThanOrEqual(1);
  } else {
    const count = await session.render(spp);
    expect(count).toBe(spp);
  }
  const data = await session.readLinear();
  const image = { ...size, channels: 4, data };
  assertNotBlank(image);
  return image;
}

export function assertNotBlank(image: LinearImage): void {
  let max = -Infinity;
  for (let p = 0; p < image.width * image.height; p++) {
    const v = image.data[p * image.channels];
    max = Math.max(max, v);
  }
  expect(max, 'image is blank (all zero)').toBeGreaterThan(0);
  expect(Number.isFinite(max), 'image has non-finite pixels').toBe(true);
}
