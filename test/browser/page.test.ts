/**
 * The interactive page end to end, in headless Chromium (SwiftShader WebGL2):
 * rendering, camera input, picking and dragging with undo, scene files and
 * links, image downloads and context loss. Everything goes through the UI
 * and its downloads; the page renders small (?maxwidth=160) to stay quick.
 */
import { readFileSync } from 'node:fs';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { decodePfm } from '../../src/image/pfm';
import { decodePng } from '../../src/cli/png';
import { projectPoint } from '../../src/scene/picking';
import { defaultScene } from '../../src/scene/presets';
import { parseSceneText } from '../../src/scene/schema';
import { serializeScene } from '../../src/scene/serialize';
import {
  canvasPixels,
  canvasPoint,
  download,
  drag,
  meanAbsDifference,
  openPage,
  savedScene,
  spp,
  waitForSpp,
  waitForRestart,
  watchRestarts,
  watchSppMinimum,
  usePageHarness,
} from '../support/page';

const fixture = (name: string) => readFileSync(new URL(`../fixtures/scenes/${name}.json`, import.meta.url));
const seed = defaultScene();
const seedAspect = seed.image.width / seed.image.height;

describe('the page', () => {
  const harness = usePageHarness();

  it('loads without console errors, renders a non-blank image and the spp count rises', async () => {
    const { page, errors } = await openPage(harness());
    expect(await page.evaluate(() => document.body.dataset.state)).toBe('ready');
    const first = await spp(page);
    await waitForSpp(page, first + 3);
    const { rgba } = await canvasPixels(page);
    let max = 0;
    let sum = 0;
    for (let i = 0; i < rgba.length; i += 4) {
      max = Math.max(max, rgba[i], rgba[i + 1], rgba[i + 2]);
      sum += rgba[i] + rgba[i + 1] + rgba[i + 2];
    }
    expect(max, 'the canvas is blank').toBeGreaterThan(100);
    expect(sum / (rgba.length / 4) / 3).toBeGreaterThan(20);
    expect(await page.getByTestId('error').isHidden()).toBe(true);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('orbits on drag and zooms on wheel: the image changes and accumulation restarts', async () => {
    const { page, errors } = await openPage(harness(), { minSpp: 6 });
    for (const gesture of ['drag', 'wheel'] as const) {
      await waitForSpp(page, 6);
      const before = await canvasPixels(page);
      const restarts = await watchRestarts(page);
      const sky = await canvasPoint(page, 0.08, 0.1);
      if (gesture === 'drag') {
        await drag(page, sky, 80, 30);
      } else {
        await page.mouse.move(sky.x, sky.y);
        await page.mouse.wheel(0, -400);
      }
      await waitForRestart(restarts); // a gesture restarts the accumulation
      await waitForSpp(page, 4);
      const after = await canvasPixels(page);
      expect(meanAbsDifference(before.rgba, after.rgba), `${gesture} changes the image`).toBeGreaterThan(4);
    }
    const camera = (await savedScene(page)).camera as { position: number[] };
    expect(camera.position).not.toEqual(seed.camera.position);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('selects a sphere by clicking it, drags it over the ground, and undo puts it back', async () => {
    const { page, errors } = await openPage(harness());
    const red = seed.spheres[0];
    const p = projectPoint(seed.camera, seedAspect, red.center)!;
    const at = await canvasPoint(page, p.u, p.v);
    await drag(page, at, 60, 0);
    // The selection outline is drawn over the canvas, not into the render.
    await page.waitForFunction(() => document.querySelector<SVGElement>('#overlay')?.style.display !== 'none');
    const moved = (await savedScene(page)).spheres as { center: number[] }[];
    expect(moved[0].center[0]).toBeGreaterThan(red.center[0] + 0.2);
    expect(moved[0].center[1]).toBeCloseTo(red.center[1], 9); // dragged over the ground: same height
    expect(moved.slice(1)).toEqual(serializeScene(seed).spheres?.slice(1));
    await page.keyboard.press('Control+z');
    expect((await savedScene(page)).spheres).toEqual(serializeScene(seed).spheres);
    await page.keyboard.press('Control+Shift+z');
    expect(((await savedScene(page)).spheres as { center: number[] }[])[0].center).toEqual(moved[0].center);
    // Shift-drag lifts; Delete removes.
    await drag(page, await canvasPoint(page, 0.5, 0.5), 0, 0); // click the centre sphere to select it
    await page.keyboard.press('Delete');
    expect(((await savedScene(page)).spheres as unknown[]).length).toBe(seed.spheres.length - 1);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('rejects a bad scene file with an alert naming the field, keeps rendering; a good file replaces the scene', async () => {
    const { page, errors } = await openPage(harness());
    const bad = JSON.parse(fixture('seed').toString('utf8'));
    bad.spheres[2].radius = -1;
    bad.camera.fov = 'wide';
    await page.setInputFiles('#file', { name: 'bad.json', mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(bad)) });
    const alert = page.getByTestId('error');
    await alert.waitFor({ state: 'visible' });
    expect(await alert.getAttribute('role')).toBe('alert');
    const text = await alert.textContent();
    expect(text).toContain('spheres[2].radius');
    expect(text).toContain('camera.fov');
    const now = await spp(page);
    await waitForSpp(page, now + 2);
    expect(await savedScene(page)).toEqual(serializeScene(seed));

    await page.setInputFiles('#file', { name: 'glossy.json', mimeType: 'application/json', buffer: fixture('glossy') });
    await alert.waitFor({ state: 'hidden' });
    expect(await savedScene(page)).toEqual(serializeScene(parseSceneText(fixture('glossy').toString('utf8'))));
    await waitForSpp(page, 2);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('round-trips a share link: the scene opened from the link is the scene shared', async () => {
    const { page, errors } = await openPage(harness());
    await page.selectOption('#examples', 'mirrors');
    const center = await canvasPoint(page, 0.5, 0.5);
    await page.mouse.move(center.x, center.y);
    await page.mouse.wheel(0, 250);
    await page.click('#share');
    await page.waitForFunction(() => location.hash.startsWith('#scene='));
    const shared = await savedScene(page);
    const link = page.url();
    const opened = await openPage(harness(), { url: link });
    expect(await savedScene(opened.page)).toEqual(shared);
    expect(await opened.page.getByTestId('error').isHidden()).toBe(true);

    // A damaged link: an alert, and the default scene instead.
    const broken = await openPage(harness(), { url: link.replace(/#scene=.*/, '#scene=not-a-scene') });
    await broken.page.getByTestId('error').waitFor({ state: 'visible' });
    expect(await savedScene(broken.page)).toEqual(serializeScene(seed));
    expect([...errors, ...opened.errors, ...broken.errors]).toEqual([]);
    await Promise.all([page.close(), opened.page.close(), broken.page.close()]);
  });

  it('downloads the displayed image as PNG and the linear image as PFM, at the render size', async () => {
    const { page, errors } = await openPage(harness(), { minSpp: 4 });
    await page.click('#pause'); // a fixed sample count while reading back
    const size = await page.getByTestId('viewport').evaluate((c: HTMLCanvasElement) => ({ width: c.width, height: c.height }));
    expect(size.width).toBe(160);
    const png = await download(page, 'save-png');
    expect(png.name).toMatch(/\.png$/);
    const image = decodePng(png.bytes);
    expect({ width: image.width, height: image.height }).toEqual(size);
    const pfm = await download(page, 'save-pfm');
    expect(pfm.name).toMatch(/\.pfm$/);
    const linear = decodePfm(pfm.bytes);
    expect({ width: linear.width, height: linear.height }).toEqual(size);
    let sum = 0;
    for (const v of linear.rgb) {
      expect(Number.isFinite(v)).toBe(true);
      sum += v;
    }
    expect(sum / linear.rgb.length).toBeGreaterThan(0.02);
    // Same picture: the PNG's top rows (sky) are bright where the PFM's are.
    const topPng = image.rgba[(2 * image.width + 2) * 4 + 2];
    const topPfm = linear.rgb[(2 * linear.width + 2) * 3 + 2];
    expect(topPng).toBeGreaterThan(0);
    expect(topPfm).toBeGreaterThan(0);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('restores a lost WebGL context by itself and the spp count rises again', async () => {
    const { page } = await openPage(harness(), { minSpp: 4 });
    const minimum = await watchSppMinimum(page);
    await page.getByTestId('viewport').evaluate((canvas: HTMLCanvasElement) => {
      canvas.getContext('webgl2')!.getExtension('WEBGL_lose_context')!.loseContext();
    });
    await page.waitForFunction(() => document.body.dataset.render === 'lost');
    await page.waitForFunction(() => document.body.dataset.render === 'rendering', undefined, { timeout: 60_000 });
    expect(await minimum()).toBe(0);
    await waitForSpp(page, 3);
    expect(await page.evaluate(() => document.body.dataset.render)).toBe('rendering');
    await page.close();
  });

  it('opens a scene dropped on the page', async () => {
    const { page, errors } = await openPage(harness());
    const text = fixture('small-light').toString('utf8');
    const dataTransfer = await page.evaluateHandle((json) => {
      const transfer = new DataTransfer();
      transfer.items.add(new File([json], 'small-light.json', { type: 'application/json' }));
      return transfer;
    }, text);
    await page.dispatchEvent('[data-testid="viewport"]', 'drop', { dataTransfer });
    await expect.poll(() => savedScene(page), { timeout: 30_000 }).toEqual(serializeScene(parseSceneText(text)));
    expect(errors).toEqual([]);
    await page.close();
  });

  it('without WebGL2 shows a clear message instead of a blank canvas', async () => {
    const page = await harness().browser.newPage({ viewport: { width: 800, height: 600 } });
    await page.addInitScript(() => {
      const original = HTMLCanvasElement.prototype.getContext;
      HTMLCanvasElement.prototype.getContext = function (this: HTMLCanvasElement, type: string, ...rest: unknown[]) {
        return type === 'webgl2' ? null : (original as (...a: unknown[]) => unknown).call(this, type, ...rest);
      } as typeof original;
    });
    await page.goto(`${harness().server.url}?maxwidth=160`);
    const alert = page.getByTestId('error');
    await alert.waitFor({ state: 'visible' });
    expect(await alert.textContent()).toContain('WebGL2 is not available');
    expect(await page.locator('.fatal h2').textContent()).toContain('WebGL2');
    await page.close();
  });
});
