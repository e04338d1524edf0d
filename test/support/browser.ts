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
): Promise<LinearImage> {
  await session.load(scene, { ...size, seed });
  const count = await session.render(spp);
  expect(count).toBe(spp);
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
