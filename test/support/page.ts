/**
 * Helpers for the page tests: one headless Chromium per file, the built page
 * (dist/web) on a loopback server, and small probes that go through the UI
 * (the spp counter, downloads, the canvas's pixels).
 */
import { readFileSync } from 'node:fs';
import type { Browser, Page } from 'playwright-core';
import { afterAll, beforeAll, expect } from 'vitest';
import { decodePng } from '../../src/cli/png';
import { launchChromium } from '../../src/node/session';
import { serveDirectory, type StaticServer } from '../../src/node/server';

export const WEB_ROOT = new URL('../../dist/web/', import.meta.url);

export interface PageHarness {
  browser: Browser;
  server: StaticServer;
}

export async function openHarness(): Promise<PageHarness> {
  const server = await serveDirectory(WEB_ROOT.pathname);
  const browser = await launchChromium();
  return { browser, server };
}

/** One browser and server per test file, closed after it: call at the top of a describe (or file). */
export function usePageHarness(): () => PageHarness {
  let harness: PageHarness | undefined;
  beforeAll(async () => {
    harness = await openHarness();
  });
  afterAll(async () => {
    await harness?.browser.close();
    await harness?.server.close();
  });
  return () => {
    if (!harness) throw new Error('the page harness failed to open');
    return harness;
  };
}

export interface OpenedPage {
  page: Page;
  /** Console errors and uncaught exceptions seen so far. */
  errors: string[];
}

/** Opens the page (small render: SwiftShader is slow) and waits until it has rendered a few samples. */
export async function openPage(
  harness: PageHarness,
  options: { hash?: string; url?: string; viewport?: { width: number; height: number }; maxWidth?: number; minSpp?: number; initScript?: () => void } = {},
): Promise<OpenedPage> {
  const page = await harness.browser.newPage({
    viewport: options.viewport ?? { width: 960, height: 600 },
    deviceScaleFactor: 1,
    acceptDownloads: true,
  });
  // Runs before the page's own scripts (to instrument WebGL or timers).
  if (options.initScript) await page.addInitScript(options.initScript);
  const errors: string[] = [];
  page.on('console', (message) => {
    if (message.type() === 'error') errors.push(message.text());
  });
  page.on('pageerror', (error) => errors.push(error.message));
  const url = options.url ?? `${harness.server.url}?maxwidth=${options.maxWidth ?? 160}${options.hash ?? ''}`;
  await page.goto(url);
  await waitForSpp(page, options.minSpp ?? 2);
  return { page, errors };
}

export async function spp(page: Page): Promise<number> {
  return Number(await page.getByTestId('spp').textContent());
}

export async function waitForSpp(page: Page, atLeast: number, timeout = 60_000): Promise<void> {
  await page.waitForFunction(
    (n) => Number(document.querySelector('[data-testid="spp"]')?.textContent) >= n,
    atLeast,
    { timeout },
  );
}

/** Starts recording the smallest spp the page shows from now on (to see a restart). */
export async function watchSppMinimum(page: Page): Promise<() => Promise<number>> {
  await page.evaluate(() => {
    const element = document.querySelector('[data-testid="spp"]')!;
    const w = window as unknown as { __sppMin: number };
    w.__sppMin = Number(element.textContent);
    new MutationObserver(() => {
      w.__sppMin = Math.min(w.__sppMin, Number(element.textContent));
    }).observe(element, { childList: true, characterData: true, subtree: true });
  });
  return () => page.evaluate(() => (window as unknown as { __sppMin: number }).__sppMin);
}

/**
 * Counts restarts of the accumulation from now on: the samples the page
 * reports (body[data-samples], complete plus the one in progress) going
 * down. Unlike the spp shown going to 0 or 1, this does not depend on how
 * many samples the machine renders in the first frame after the restart.
 */
export async function watchRestarts(page: Page): Promise<() => Promise<number>> {
  await page.evaluate(() => {
    const w = window as unknown as { __restarts: number };
    let previous = Number(document.body.dataset.samples);
    w.__restarts = 0;
    new MutationObserver(() => {
      const samples = Number(document.body.dataset.samples);
      if (samples < previous) w.__restarts += 1;
      previous = samples;
    }).observe(document.body, { attributes: true, attributeFilter: ['data-samples'] });
  });
  return () => page.evaluate(() => (window as unknown as { __restarts: number }).__restarts);
}

/** Waits for the accumulation to restart (see watchRestarts). */
export async function waitForRestart(restarts: () => Promise<number>, timeout = 30_000): Promise<void> {
  await expect.poll(restarts, { timeout, interval: 50 }).toBeGreaterThan(0);
}

/** The canvas as the page shows it, RGBA8. */
export async function canvasPixels(page: Page): Promise<{ width: number; height: number; rgba: Uint8Array }> {
  return decodePng(await page.getByTestId('viewport').screenshot());
}

export function meanAbsDifference(a: Uint8Array, b: Uint8Array): number {
  expect(a.length).toBe(b.length);
  let sum = 0;
  for (let i = 0; i < a.length; i += 4) sum += Math.abs(a[i] - b[i]) + Math.abs(a[i + 1] - b[i + 1]) + Math.abs(a[i + 2] - b[i + 2]);
  return sum / (a.length / 4) / 3;
}

/** Clicks a toolbar button that downloads a file; returns the file's bytes and name. */
export async function download(page: Page, buttonId: string): Promise<{ name: string; bytes: Buffer }> {
  const [event] = await Promise.all([page.waitForEvent('download'), page.click(`#${buttonId}`)]);
  const path = await event.path();
  return { name: event.suggestedFilename(), bytes: readFileSync(path) };
}

/** The scene as "Save JSON" writes it. */
export async function savedScene(page: Page): Promise<Record<string, unknown>> {
  const { name, bytes } = await download(page, 'save-json');
  expect(name).toMatch(/\.json$/);
  return JSON.parse(bytes.toString('utf8'));
}

/** Client coordinates of image point (u, v) on the canvas. */
export async function canvasPoint(page: Page, u: number, v: number): Promise<{ x: number; y: number }> {
  const box = (await page.getByTestId('viewport').boundingBox())!;
  return { x: box.x + u * box.width, y: box.y + v * box.height };
}

export async function drag(page: Page, from: { x: number; y: number }, dx: number, dy: number, shift = false): Promise<void> {
  if (shift) await page.keyboard.down('Shift');
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  await page.mouse.move(from.x + dx, from.y + dy, { steps: 8 });
  await page.mouse.up();
  if (shift) await page.keyboard.up('Shift');
}

export interface Probe {
  links: number;
  frames: number[];
}

/**
 * Counts program links and records animation-frame times (to see a freeze):
 * pass to openPage's initScript, read with probe(page).
 */
export function instrument(): void {
  const probe = { links: 0, frames: [] as number[] };
  (window as unknown as { __probe: Probe }).__probe = probe;
  const link = WebGL2RenderingContext.prototype.linkProgram;
  WebGL2RenderingContext.prototype.linkProgram = function (this: WebGL2RenderingContext, program: WebGLProgram) {
    probe.links += 1;
    return link.call(this, program);
  };
  const tick = (time: number) => {
    probe.frames.push(time);
    requestAnimationFrame(tick);
  };
  requestAnimationFrame(tick);
}

export const probe = (page: Page) => page.evaluate(() => (window as unknown as { __probe: Probe }).__probe);
