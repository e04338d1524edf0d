/**
 * Environment maps on the page, end to end in headless Chromium: the
 * Environment folder's picker (bundled maps, none, constant sky), intensity
 * and rotation without a new shader program (WebGL linkProgram calls are
 * counted), a share link carrying a bundled map, the example with a map, a
 * user's .hdr opened or dropped, a broken map rejected without changing
 * anything, and a 2k map decoded off the main thread (its times are logged).
 */
import { readFileSync } from 'node:fs';
import type { Locator, Page } from 'playwright-core';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import type { MapTimings } from '../../src/app/mapDecoder';
import { sceneFromHash, shareHash } from '../../src/app/files';
import { defaultScene } from '../../src/scene/presets';
import type { Scene } from '../../src/scene/types';
import { openPage, savedScene, spp, waitForSpp, watchSppMinimum, usePageHarness, instrument, probe } from '../support/page';
import { encodeFlatHdr } from '../support/rgbe';

const fixture = (path: string) => readFileSync(new URL(`../fixtures/${path}`, import.meta.url));

const now = (page: Page) => page.evaluate(() => performance.now());

async function longestFrameGap(page: Page, since: number): Promise<number> {
  const frames = (await probe(page)).frames.filter((t) => t >= since);
  let gap = 0;
  for (let i = 1; i < frames.length; i++) gap = Math.max(gap, frames[i] - frames[i - 1]);
  return gap;
}

const folder = (page: Page) => page.locator('#panel .lil-gui').filter({ has: page.locator(':scope > .lil-title', { hasText: /^Environment$/ }) });

function control(page: Page, name: string): Locator {
  return folder(page).locator('.lil-controller').filter({ has: page.locator('.lil-name', { hasText: new RegExp(`^${name.replace(/[()]/g, '\\$&')}$`) }) });
}

async function openFolder(page: Page): Promise<void> {
  const f = folder(page);
  if (await f.evaluate((e) => e.classList.contains('lil-closed'))) await f.locator(':scope > .lil-title').click();
  await control(page, 'environment').locator('select').waitFor();
}

/** Picks an option of the environment picker by its label, as a user does. */
async function pick(page: Page, label: string): Promise<void> {
  await control(page, 'environment').locator('select').selectOption({ label });
}

async function enter(field: Locator, value: string): Promise<void> {
  await field.fill(value);
  await field.press('Enter');
  await field.blur();
}

const mapTimings = (page: Page) => page.evaluate(() => (window as unknown as { __mapTimings?: MapTimings }).__mapTimings ?? null);

async function waitForMap(page: Page, name: string): Promise<MapTimings> {
  await page.waitForFunction((n) => (window as unknown as { __mapTimings?: MapTimings }).__mapTimings?.name === n, name, { timeout: 60_000 });
  return (await mapTimings(page))!;
}

const environmentOf = async (page: Page) => (await savedScene(page)).environment as Record<string, unknown> | undefined;

describe('environment maps on the page', () => {
  const harness = usePageHarness();

  it('bundled maps: picker, intensity and rotation without a new program, a share link that carries the map', async () => {
    const { page, errors } = await openPage(harness(), { initScript: instrument });
    await openFolder(page);
    const note = page.getByTestId('map-note');
    expect(await note.textContent()).toMatch(/link cannot carry/);

    await pick(page, 'map: studio');
    const studio = await waitForMap(page, 'bundled/studio.exr');
    expect(studio).toMatchObject({ width: 512, height: 256, offMainThread: true });
    await waitForSpp(page, 2);
    expect(await environmentOf(page)).toEqual({ map: 'bundled/studio.exr', intensity: 1, rotation: 0 });
    expect(await control(page, 'rotation (deg)').isVisible()).toBe(true);
    expect(await control(page, 'color').isVisible(), 'the constant color is hidden with a map').toBe(false);

    // Intensity and rotation: uniforms, no program; another map: the same program.
    const links = (await probe(page)).links;
    await enter(control(page, 'intensity').locator('input'), '2.5');
    await enter(control(page, 'rotation (deg)').locator('input'), '90');
    expect(await environmentOf(page)).toEqual({ map: 'bundled/studio.exr', intensity: 2.5, rotation: 90 });
    await pick(page, 'map: city');
    await waitForMap(page, 'bundled/city.exr');
    await waitForSpp(page, 2);
    expect(await environmentOf(page)).toEqual({ map: 'bundled/city.exr', intensity: 2.5, rotation: 90 });
    expect((await probe(page)).links - links, 'intensity, rotation and another map link no program').toBe(0);

    // The share link carries the bundled map's name; a link naming a map
    // this page never loaded (park) is resolved from the bundle.
    await page.click('#share');
    const shared = sceneFromHash(await page.evaluate(() => location.hash));
    expect(shared?.ok && shared.scene.environment).toEqual({ map: 'bundled/city.exr', intensity: 2.5, rotation: 90 });
    const parkScene = { ...defaultScene(), version: 2, environment: { map: 'bundled/park.exr', intensity: 1.5, rotation: -45 } } as Scene;
    await page.evaluate((hash) => (location.hash = hash), shareHash(parkScene));
    expect(await waitForMap(page, 'bundled/park.exr')).toMatchObject({ offMainThread: true });
    expect(await environmentOf(page)).toEqual({ map: 'bundled/park.exr', intensity: 1.5, rotation: -45 });
    expect(await page.getByTestId('error').isHidden()).toBe(true);

    // Back to a constant sky and to none; undo returns the map.
    await pick(page, 'constant color');
    expect((await environmentOf(page))?.color).toBeDefined();
    await pick(page, 'none (black)');
    expect(await environmentOf(page)).toBeUndefined();
    await page.click('#undo');
    await page.click('#undo');
    expect(await environmentOf(page)).toEqual({ map: 'bundled/park.exr', intensity: 1.5, rotation: -45 });
    expect((await probe(page)).links - links, 'no edit of this test after the first map needed a new program').toBe(0);

    // The example with a map is listed (its scene is checked in test/unit/bundled-maps.test.ts).
    expect(await page.locator('#examples option').allTextContents()).toContain('environment map');
    expect(errors).toEqual([]);
  });

  it("a user's map: opened, rejected when broken (nothing changes), dropped, a 2k map off the main thread", async () => {
    const { page, errors } = await openPage(harness(), { initScript: instrument });
    await page.setInputFiles('#file', { name: 'gradient.hdr', mimeType: 'application/octet-stream', buffer: fixture('envmaps/gradient-rle.hdr') });
    await waitForMap(page, 'gradient.hdr');
    expect(await environmentOf(page)).toEqual({ map: 'gradient.hdr', intensity: 1, rotation: 0 });
    await openFolder(page);
    expect(await control(page, 'environment').locator('.lil-display').textContent()).toBe('gradient.hdr');

    // The link cannot carry it: the share notice says so.
    await page.click('#share');
    await expect.poll(() => page.getByTestId('notice').textContent()).toMatch(/your file "gradient.hdr", which a link cannot carry/);

    // A truncated map: rejected naming environment.map; the scene and the samples stay.
    await waitForSpp(page, (await spp(page)) + 2);
    const before = await spp(page); // first: the watch starts at the count shown then, which may be higher
    const sppMinimum = await watchSppMinimum(page);
    await page.setInputFiles('#file', { name: 'broken.exr', mimeType: 'application/octet-stream', buffer: fixture('envmaps/studio.exr').subarray(0, 2000) });
    const alert = page.getByTestId('error');
    await alert.waitFor({ state: 'visible' });
    expect(await alert.textContent()).toMatch(/environment\.map: "broken\.exr": /);
    await waitForSpp(page, before + 2);
    expect(await sppMinimum(), 'the rejected map restarted the render').toBeGreaterThanOrEqual(before);
    expect(await environmentOf(page)).toEqual({ map: 'gradient.hdr', intensity: 1, rotation: 0 });

    // A map dropped on the page.
    const small = Array.from(encodeFlatHdr(8, 4, (x) => [x / 8, 0.5, 1]));
    await page.evaluate((bytes) => {
      const data = new DataTransfer();
      data.items.add(new File([new Uint8Array(bytes)], 'dropped.hdr'));
      window.dispatchEvent(new DragEvent('drop', { dataTransfer: data, bubbles: true, cancelable: true }));
    }, small);
    await waitForMap(page, 'dropped.hdr');
    expect((await environmentOf(page))?.map).toBe('dropped.hdr');
    expect(await alert.isHidden(), 'a map that loads clears the old error').toBe(true);

    // A 2k map: decoded and its distribution built in the Worker.
    const big = encodeFlatHdr(2048, 1024, (x, y) => [1 + Math.sin(x / 50) ** 2, 1 + y / 1024, (x * y) % 7 === 0 ? 40 : 1]);
    await waitForSpp(page, (await spp(page)) + 2);
    const usualGap = await longestFrameGap(page, (await now(page)) - 3000);
    // From the input's change event: Playwright hands the 8 MB file to the page on its main thread first.
    await page.evaluate(() => document.getElementById('file')!.addEventListener('change', () => ((window as unknown as { __changeAt: number }).__changeAt = performance.now()), { once: true, capture: true }));
    await page.setInputFiles('#file', { name: 'big.hdr', mimeType: 'application/octet-stream', buffer: Buffer.from(big) });
    await waitForMap(page, 'big.hdr');
    await waitForSpp(page, 2);
    const timings = (await mapTimings(page))!;
    const since = await page.evaluate(() => (window as unknown as { __changeAt: number }).__changeAt);
    const gap = await longestFrameGap(page, since);
    console.log(
      `2k map in the page: decode ${timings.decodeMs.toFixed(0)} ms + distribution ${timings.distributionMs.toFixed(0)} ms in the Worker, ` +
        `${timings.totalMs.toFixed(0)} ms until back; applying it (texture upload queued) ${timings.applyMs?.toFixed(0)} ms on the main thread; longest frame gap meanwhile ${gap.toFixed(0)} ms (before: ${usualGap.toFixed(0)} ms)`,
    );
    expect(timings).toMatchObject({ width: 2048, height: 1024, offMainThread: true });
    expect(errors).toEqual([]);
  });
});
