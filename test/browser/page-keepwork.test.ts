/**
 * The page never loses the user's work (issue 13), in headless Chromium:
 * a rejected file changes nothing (not even the accumulated samples), the
 * work survives a reload through the IndexedDB autosave (scene, camera, view
 * settings, undo), a corrupt saved state is discarded with a notice, a share
 * link opens over the saved scene without losing it, "New scene" is one Undo
 * from the work, and a lost WebGL context resumes from the last snapshot.
 */
import { readFileSync } from 'node:fs';
import type { Page } from 'playwright-core';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { shareHash } from '../../src/app/files';
import { MAX_SAVED_CHARS, SAVED_FORMAT, SAVED_VERSION } from '../../src/app/savedState';
import { defaultScene } from '../../src/scene/presets';
import { parseSceneText } from '../../src/scene/schema';
import { serializeScene } from '../../src/scene/serialize';
import { waitSaved, writeSavedRecord } from '../support/keepwork';
import {
  canvasPixels,
  canvasPoint,
  drag,
  meanAbsDifference,
  openPage,
  savedScene,
  spp,
  waitForSpp,
  watchSppMinimum,
  usePageHarness,
} from '../support/page';

const fixtureBytes = (path: string) => readFileSync(new URL(`../fixtures/${path}`, import.meta.url));
const fixtureText = (name: string) => readFileSync(new URL(`../fixtures/scenes/${name}.json`, import.meta.url), 'utf8');
const defaultJson = serializeScene(defaultScene());
const renderState = (page: Page) => page.evaluate(() => document.body.dataset.render);
const canvasSize = (page: Page) =>
  page.getByTestId('viewport').evaluate((c: HTMLCanvasElement) => ({ width: c.width, height: c.height }));
const sleep = (ms: number) => new Promise((resolve) => setTimeout(resolve, ms));

async function openBadFile(page: Page, name: string, text: string): Promise<void> {
  await page.setInputFiles('#file', { name, mimeType: 'application/json', buffer: Buffer.from(text) });
  await page.getByTestId('error').waitFor({ state: 'visible' });
}

/** A panel control's text input, by its label. */
const control = (page: Page, label: string) =>
  page.locator('#panel .lil-controller', { hasText: label }).first().locator('input[type="text"], input[type="number"]').first();

async function setControl(page: Page, label: string, value: string): Promise<void> {
  const input = control(page, label);
  await input.fill(value);
  await input.evaluate((element: HTMLInputElement) => {
    element.dispatchEvent(new Event('change', { bubbles: true }));
    element.blur();
  });
}

describe('the page keeps the work', () => {
  const harness = usePageHarness();

  it('a rejected scene file changes nothing: scene, selection, undo, render size, samples', async () => {
    // No render-width cap and a short window: the render size follows the layout's height, as for a user.
    const { page, errors } = await openPage(harness(), { viewport: { width: 1000, height: 420 }, maxWidth: 100_000, minSpp: 3 });
    await page.click('#add-sphere'); // an undo step and a selection
    await waitForSpp(page, 3);
    const scene = await savedScene(page);
    const size = await canvasSize(page);
    const before = await spp(page);
    const minimum = await watchSppMinimum(page);
    const bad = JSON.parse(fixtureText('seed'));
    bad.spheres[0].radius = -1;
    await openBadFile(page, 'bad.json', JSON.stringify(bad));
    await waitForSpp(page, before + 3);
    expect(await minimum(), 'the spp count never went down').toBeGreaterThanOrEqual(before);
    expect(await canvasSize(page)).toEqual(size);
    expect(await savedScene(page)).toEqual(scene);
    expect(await page.locator('#delete').isDisabled(), 'the selection is kept').toBe(false);
    expect(await page.locator('#undo').isDisabled(), 'the undo history is kept').toBe(false);

    // Paused: the canvas is bit-identical through a second rejected file.
    await page.click('#pause');
    await page.waitForFunction(() => document.body.dataset.render === 'paused');
    await page.click('.alert .dismiss'); // the alert floats over the canvas: out of the screenshots
    const count = await spp(page);
    const image = await canvasPixels(page);
    await openBadFile(page, 'broken.json', '{"camera": ');
    await sleep(500);
    await page.click('.alert .dismiss');
    expect(await spp(page)).toBe(count);
    expect(meanAbsDifference(image.rgba, (await canvasPixels(page)).rgba)).toBe(0);
    await page.keyboard.press('Control+z');
    expect(await savedScene(page), 'undo still undoes the added sphere').toEqual(defaultJson);
    expect(errors).toEqual([]);
    await page.close();
  });

  const assetFailures: [string, string, { name: string; buffer: Buffer }[], RegExp][] = [
    ['a map that does not decode', 'envmap', [{ name: 'sunset.hdr', buffer: Buffer.from('#?RADIANCE\nnot really\n') }], /environment\.map: "\.\.\/envmaps\/sunset\.hdr"/],
    ['a map not opened with the scene', 'envmap', [], /environment\.map: .*not opened/],
    ['a model that does not decode', 'bunny', [
      { name: 'bunny.ply', buffer: Buffer.from('ply\nformat ascii 1.0\nelement vertex 3\nend_header\n1 2\n') },
      { name: 'gem.obj', buffer: fixtureBytes('meshes/gem.obj') },
    ], /meshes\[0\]\.file: "\.\.\/meshes\/bunny\.ply"/],
  ];
  for (const [what, sceneName, files, issue] of assetFailures) {
    it(`a scene with ${what} is rejected and changes nothing`, async () => {
      const { page, errors } = await openPage(harness(), { minSpp: 3 });
      await page.click('#add-sphere');
      const scene = await savedScene(page);
      const before = await spp(page);
      const minimum = await watchSppMinimum(page);
      await page.setInputFiles('#file', [
        { name: `${sceneName}.json`, mimeType: 'application/json', buffer: Buffer.from(fixtureText(sceneName)) },
        ...files.map((f) => ({ ...f, mimeType: 'application/octet-stream' })),
      ]);
      await page.getByTestId('error').waitFor({ state: 'visible' });
      expect(await page.getByTestId('error').textContent()).toMatch(issue);
      await waitForSpp(page, before + 2);
      expect(await minimum()).toBeGreaterThanOrEqual(before);
      expect(await savedScene(page)).toEqual(scene);
      expect(await page.locator('#delete').isDisabled(), 'the selection is kept').toBe(false);
      expect(errors).toEqual([]);
      await page.close();
    });
  }

  it('opens a scene with its map, keeps the map with the autosave, and reopens both after a reload', async () => {
    const { page, errors } = await openPage(harness());
    const envmap = serializeScene(parseSceneText(fixtureText('envmap')));
    await page.setInputFiles('#file', [
      { name: 'envmap.json', mimeType: 'application/json', buffer: Buffer.from(fixtureText('envmap')) },
      { name: 'sunset.hdr', mimeType: 'application/octet-stream', buffer: fixtureBytes('envmaps/sunset.hdr') },
    ]);
    await expect.poll(() => savedScene(page), { timeout: 30_000 }).toEqual(envmap);
    await page.click('#add-sphere');
    const edited = await savedScene(page);
    await waitSaved(page);
    await page.reload();
    await waitForSpp(page, 2);
    expect(await savedScene(page)).toEqual(edited);
    expect(await page.getByTestId('notice').textContent()).not.toContain('discarded');
    await page.keyboard.press('Control+z');
    expect(await savedScene(page)).toEqual(envmap);
    await page.keyboard.press('Control+z');
    expect(await savedScene(page)).toEqual(defaultJson);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('brings back the scene, camera, view settings and undo history after a reload', async () => {
    const { page, errors } = await openPage(harness());
    await page.click('#add-sphere');
    await setControl(page, 'color', '#20c040'); // the new (selected) sphere's colour
    await setControl(page, 'exposure (stops)', '1.5');
    const coloured = await savedScene(page);
    expect((coloured.spheres as { material: { color: number[] } }[]).at(-1)!.material.color[0]).toBeLessThan(0.1);
    await drag(page, await canvasPoint(page, 0.08, 0.1), 70, 20); // orbit the camera
    const edited = await savedScene(page);
    expect(edited.camera).not.toEqual(coloured.camera);
    await waitSaved(page);

    await page.reload();
    await waitForSpp(page, 2);
    expect(await savedScene(page)).toEqual(edited);
    expect(Number(await control(page, 'exposure (stops)').inputValue())).toBeCloseTo(1.5, 6);
    expect(await page.getByTestId('notice').textContent()).toContain('Restored');
    await page.keyboard.press('Control+z');
    expect(await savedScene(page), 'undo goes back to before the camera move').toEqual(coloured);
    await page.keyboard.press('Control+z');
    await page.keyboard.press('Control+z');
    expect(await savedScene(page), 'and on to the example').toEqual(defaultJson);
    expect(errors).toEqual([]);
    await page.close();
  });

  const validRecord = (scene: unknown) =>
    JSON.stringify({
      format: SAVED_FORMAT, version: SAVED_VERSION, savedAt: 0, scene, homeCamera: defaultJson.camera,
      view: { exposure: 0, toneMap: 'aces', targetSpp: 0 }, undo: [], redo: [], linkDigest: null, assets: [],
    });
  const corrupt: [string, () => unknown][] = [
    ['invalid JSON', () => '{"format": "pathtrace-autosave", "version": 1, "scene": {'],
    ['an invalid scene', () => validRecord({ ...defaultJson, camera: { ...defaultJson.camera, fov: 'wide' } })],
    ['an oversized record', () => validRecord(defaultJson) + ' '.repeat(MAX_SAVED_CHARS)],
    ['not text', () => ({ scene: defaultJson })],
  ];
  for (const [what, record] of corrupt) {
    it(`discards a saved state with ${what}: a notice and the example scene`, async () => {
      const { page, errors } = await openPage(harness());
      await page.selectOption('#examples', 'mirrors');
      await waitSaved(page);
      await writeSavedRecord(page, record());
      await page.reload();
      await waitForSpp(page, 2);
      const notice = page.getByTestId('notice');
      expect(await notice.isVisible()).toBe(true);
      expect(await notice.textContent()).toMatch(/saved scene was discarded because/);
      expect(await savedScene(page)).toEqual(defaultJson);
      expect(await page.evaluate(() => document.body.dataset.state)).toBe('ready');
      expect(errors).toEqual([]);
      await page.close();
    });
  }

  it('a share link opens its scene; the saved scene is one Undo away, and reloading the link keeps edits', async () => {
    const { page, errors } = await openPage(harness());
    await page.click('#add-sphere');
    const mine = await savedScene(page);
    await waitSaved(page);
    const glossy = serializeScene(parseSceneText(fixtureText('glossy')));
    const link = `${harness().server.url}?maxwidth=161${shareHash(parseSceneText(fixtureText('glossy')))}`;
    await page.goto(link);
    await waitForSpp(page, 2);
    expect(await savedScene(page)).toEqual(glossy);
    expect(await page.getByTestId('notice').textContent()).toContain('one Undo away');
    await page.keyboard.press('Control+z');
    expect(await savedScene(page)).toEqual(mine);
    await page.keyboard.press('Control+Shift+z');
    await page.click('#add-light'); // an edit of the linked scene
    const linkEdited = await savedScene(page);
    await waitSaved(page);
    await page.reload();
    await waitForSpp(page, 2);
    expect(await savedScene(page), 'the same link again keeps the edits made since').toEqual(linkEdited);
    await page.keyboard.press('Control+z');
    await page.keyboard.press('Control+z');
    expect(await savedScene(page), 'and the scene before the link is still there').toEqual(mine);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('"New scene" opens the example and Undo brings the work back', async () => {
    const { page, errors } = await openPage(harness());
    await page.selectOption('#examples', 'small-light');
    await page.click('#add-sphere');
    const work = await savedScene(page);
    await page.click('#new-scene');
    await expect.poll(() => savedScene(page)).toEqual(defaultJson);
    await page.keyboard.press('Control+z');
    expect(await savedScene(page)).toEqual(work);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('leaving a saved page does not ask', async () => {
    const { page } = await openPage(harness());
    await page.click('#add-sphere');
    await waitSaved(page);
    const asked = await page.evaluate(() => {
      const event = new Event('beforeunload', { cancelable: true });
      window.dispatchEvent(event);
      return event.defaultPrevented;
    });
    expect(asked).toBe(false);
    await page.close();
  });

  it('when nothing can be saved: says so, keeps rendering, and asks before the page is left', async () => {
    const page = await harness().browser.newPage({ viewport: { width: 960, height: 600 } });
    await page.addInitScript(() => {
      indexedDB.open = () => {
        throw new DOMException('storage is disabled', 'SecurityError');
      };
    });
    await page.goto(`${harness().server.url}?maxwidth=160`);
    await waitForSpp(page, 2);
    await page.click('#add-sphere');
    await page.waitForFunction(() => document.body.dataset.saved === 'failed');
    expect(await page.getByTestId('saved').textContent()).toContain('not saved');
    // Headless Chromium shows no beforeunload prompt; a cancelled event is what makes browsers ask.
    const cancelled = () =>
      page.evaluate(() => {
        const event = new Event('beforeunload', { cancelable: true });
        window.dispatchEvent(event);
        return event.defaultPrevented;
      });
    expect(await cancelled(), 'leaving asks first').toBe(true);
    await waitForSpp(page, (await spp(page)) + 2);
    await page.close();
  });

  it('a lost and restored WebGL context resumes from the last snapshot of the samples', async () => {
    const { page, errors } = await openPage(harness(), { minSpp: 4 });
    const loseContext = () =>
      page.getByTestId('viewport').evaluate((canvas: HTMLCanvasElement) => {
        canvas.getContext('webgl2')!.getExtension('WEBGL_lose_context')!.loseContext();
      });
    // Paused: the snapshot holds exactly the image shown, so it comes back bit for bit.
    await page.click('#pause');
    const messages = await page.addStyleTag({ content: '.messages { visibility: hidden !important; }' }); // they float over the canvas
    await sleep(3000); // > one snapshot interval (2 s)
    const count = await spp(page);
    const image = await canvasPixels(page);
    await loseContext();
    await page.waitForFunction(() => document.body.dataset.render === 'lost');
    await page.waitForFunction(() => document.body.dataset.render === 'paused', undefined, { timeout: 30_000 });
    expect(await spp(page), (await page.getByTestId('notice').textContent()) ?? '').toBe(count);
    expect(meanAbsDifference(image.rgba, (await canvasPixels(page)).rgba)).toBe(0);
    await messages.evaluate((style) => (style as HTMLElement).remove());
    expect(await page.getByTestId('notice').textContent()).toContain(`resumes from ${count} spp`);

    // Rendering: at most one snapshot interval of samples is redone.
    await page.click('#pause');
    await waitForSpp(page, count + 4);
    const earlier = await spp(page);
    await sleep(3000);
    await loseContext();
    await page.waitForFunction(() => document.body.dataset.render === 'lost');
    await page.waitForFunction(() => document.body.dataset.render === 'rendering', undefined, { timeout: 30_000 });
    const resumed = await spp(page);
    expect(resumed).toBeGreaterThanOrEqual(earlier);
    expect(await renderState(page)).toBe('rendering');

    // Hidden (a background tab, where contexts get reclaimed): a snapshot is taken at once.
    await waitForSpp(page, resumed + 4);
    const atHide = await page.evaluate(() => {
      Object.defineProperty(document, 'visibilityState', { configurable: true, get: () => 'hidden' });
      document.dispatchEvent(new Event('visibilitychange'));
      return Number(document.querySelector('[data-testid="spp"]')!.textContent);
    });
    await loseContext();
    await page.waitForFunction(() => document.body.dataset.render === 'lost');
    await page.waitForFunction(() => document.body.dataset.render === 'rendering', undefined, { timeout: 30_000 });
    expect(await spp(page)).toBeGreaterThanOrEqual(atHide);
    expect(errors).toEqual([]);
    await page.close();
  });
});
