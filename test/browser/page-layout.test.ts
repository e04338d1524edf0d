/**
 * The page's layout at desktop (1280x800) and phone (390x844) sizes: the
 * toolbar, the canvas, the statistics and the panel do not overlap, text is
 * of a legible size, and the panel collapses. Writes screenshots to
 * test-output/screenshots/ to look at; with UPDATE_SCREENSHOTS=1 it writes
 * the README's, in docs/screenshots/, instead.
 */
import { mkdirSync, writeFileSync } from 'node:fs';
import type { Page } from 'playwright-core';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { decodePng, encodePng } from '../../src/cli/png';
import { projectPoint } from '../../src/scene/picking';
import { defaultScene } from '../../src/scene/presets';
import { canvasPoint, drag, openHarness, openPage, waitForSpp, type PageHarness } from '../support/page';

const SHOTS = new URL(process.env.UPDATE_SCREENSHOTS ? '../../docs/screenshots/' : '../../test-output/screenshots/', import.meta.url);

type Box = { x: number; y: number; width: number; height: number };
const overlaps = (a: Box, b: Box) =>
  a.x < b.x + b.width - 0.5 && b.x < a.x + a.width - 0.5 && a.y < b.y + b.height - 0.5 && b.y < a.y + a.height - 0.5;

async function boxes(page: Page): Promise<Record<string, Box>> {
  const result: Record<string, Box> = {};
  for (const [name, selector] of Object.entries({ toolbar: '.toolbar', canvas: '[data-testid="viewport"]', status: '#status', panel: '#panel' })) {
    result[name] = (await page.locator(selector).boundingBox())!;
    expect(result[name], `${name} is laid out`).toBeTruthy();
  }
  return result;
}

async function assertLayout(page: Page, viewport: { width: number; height: number }): Promise<void> {
  const b = await boxes(page);
  const names = Object.keys(b);
  for (let i = 0; i < names.length; i++) {
    for (let j = i + 1; j < names.length; j++) expect(overlaps(b[names[i]], b[names[j]]), `${names[i]} overlaps ${names[j]}`).toBe(false);
  }
  for (const name of ['toolbar', 'canvas', 'status']) {
    expect(b[name].x).toBeGreaterThanOrEqual(0);
    expect(b[name].x + b[name].width, `${name} fits the width`).toBeLessThanOrEqual(viewport.width + 0.5);
  }
  expect(b.canvas.width).toBeGreaterThan(viewport.width * 0.6 - 300);
  // Legible: no text under 11 px in the toolbar, statistics and panel.
  const smallest = await page.evaluate(() =>
    Math.min(...[...document.querySelectorAll('.toolbar button, .toolbar select, #status, .lil-gui .lil-name')].map((e) => parseFloat(getComputedStyle(e).fontSize))),
  );
  expect(smallest).toBeGreaterThanOrEqual(11);
  // The toolbar's buttons do not overlap each other (it wraps on narrow screens).
  const buttons = await page.locator('.toolbar button, .toolbar select').evaluateAll((elements) =>
    elements.map((e) => {
      const r = e.getBoundingClientRect();
      return { x: r.x, y: r.y, width: r.width, height: r.height };
    }),
  );
  for (let i = 0; i < buttons.length; i++) {
    for (let j = i + 1; j < buttons.length; j++) expect(overlaps(buttons[i], buttons[j]), `toolbar controls ${i} and ${j} overlap`).toBe(false);
  }
}

/** Clicks the panel's title and waits for its open/close animation to finish. */
async function togglePanel(page: Page): Promise<boolean> {
  const closed = await page.locator('#panel .lil-gui.lil-root').evaluate((e) => e.classList.contains('lil-closed'));
  await page.locator('#panel .lil-gui.lil-root > .lil-title').click();
  await page.waitForFunction((was) => {
    const root = document.querySelector('#panel .lil-gui.lil-root')!;
    const children = root.querySelector<HTMLElement>(':scope > .lil-children')!;
    return root.classList.contains('lil-closed') !== was && !root.classList.contains('lil-transition') && children.style.height === '';
  }, closed);
  return page.locator('#panel .lil-gui.lil-root').evaluate((e) => e.classList.contains('lil-closed'));
}

/** The panel collapses and opens from its title bar. */
async function assertPanelCollapses(page: Page): Promise<void> {
  const wasClosed = await page.locator('#panel .lil-gui.lil-root').evaluate((e) => e.classList.contains('lil-closed'));
  expect(await togglePanel(page)).toBe(!wasClosed);
  expect(await togglePanel(page)).toBe(wasClosed);
}

/** A 2x2 box-filtered copy of a PNG: keeps the README's screenshots small. */
function halfSize(png: Uint8Array): Buffer {
  const image = decodePng(png);
  const width = image.width >> 1;
  const height = image.height >> 1;
  const out = new Uint8Array(width * height * 4);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      for (let c = 0; c < 4; c++) {
        const at = (yy: number, xx: number) => image.rgba[(yy * image.width + xx) * 4 + c];
        const sum = at(2 * y, 2 * x) + at(2 * y, 2 * x + 1) + at(2 * y + 1, 2 * x) + at(2 * y + 1, 2 * x + 1);
        out[(y * width + x) * 4 + c] = Math.round(sum / 4);
      }
    }
  }
  return encodePng(width, height, out);
}

describe('page layout', () => {
  let harness: PageHarness;
  beforeAll(async () => {
    harness = await openHarness();
    mkdirSync(SHOTS, { recursive: true });
  });
  afterAll(async () => {
    await harness?.browser.close();
    await harness?.server.close();
  });

  it('desktop 1280x800: nothing overlaps, the panel collapses; screenshot', async () => {
    const viewport = { width: 1280, height: 800 };
    const { page, errors } = await openPage(harness, { viewport, maxWidth: 480 });
    await assertLayout(page, viewport);
    await assertPanelCollapses(page);
    // Select the gold sphere to show the selection outline and its controls.
    const seed = defaultScene();
    const gold = projectPoint(seed.camera, seed.image.width / seed.image.height, seed.spheres[2].center)!;
    await drag(page, await canvasPoint(page, gold.u, gold.v), 0, 0);
    await waitForSpp(page, 24, 120_000);
    writeFileSync(new URL('desktop.png', SHOTS), halfSize(await page.screenshot()));
    expect(errors).toEqual([]);
    await page.close();
  });

  it('phone 390x844: nothing overlaps, the panel starts collapsed and opens; screenshot', async () => {
    const viewport = { width: 390, height: 844 };
    const { page, errors } = await openPage(harness, { viewport, maxWidth: 390 });
    await assertLayout(page, viewport);
    expect(await page.locator('#panel .lil-gui.lil-root').evaluate((e) => e.classList.contains('lil-closed'))).toBe(true);
    await assertPanelCollapses(page);
    await waitForSpp(page, 24, 120_000);
    writeFileSync(new URL('phone.png', SHOTS), await page.screenshot());
    expect(await togglePanel(page)).toBe(false);
    await assertLayout(page, viewport);
    writeFileSync(new URL('phone-panel.png', SHOTS), await page.screenshot({ fullPage: true }));
    expect(errors).toEqual([]);
    await page.close();
  });
});
