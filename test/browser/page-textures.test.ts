/**
 * Texture slots on the page, end to end in headless Chromium: the bundled
 * `textured` example renders; a PNG dropped on a mesh's constant roughness
 * makes it a texture (the slot shows the image's name and size; the render
 * changes); a corrupt PNG opened on a slot is rejected naming its key and
 * changes nothing (scene, samples); clearing the texture brings the
 * constant, and the very image, back; the image is kept with the autosave.
 *
 * The render stops at a fixed spp ("stop at spp"): the page's images are
 * deterministic, so the same scene gives the same pixels and a change of
 * the image is the change of the scene, not noise.
 *
 * Nearly all of its time is the one compile of the example's program on
 * SwiftShader (65-135 s measured on the shared 2-core machine, the page
 * blocked meanwhile; the rest takes about 8 s), most of it for the normal
 * map: a 1-spp CLI render of textured.json takes 56 s, 17 s without its
 * normal map.
 */
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import type { Locator, Page } from 'playwright-core';
import { describe, expect, it } from 'vitest';
import { canvasPixels, canvasPoint, meanAbsDifference, openPage, savedScene, spp, usePageHarness, waitForRestart, watchRestarts } from '../support/page';

const CHECKER = fileURLToPath(new URL('../fixtures/textures/checker.png', import.meta.url));
const STOP_AT = 2;

type SavedMesh = { file: string; material: Record<string, unknown> };
const meshesOf = async (page: Page) => ((await savedScene(page)).meshes ?? []) as SavedMesh[];

/** A controller by its exact label, in the selection folder (the panel's first) unless `anywhere`. */
const control = (page: Page, label: string, anywhere = false): Locator =>
  (anywhere ? page : page.locator('.lil-root > .lil-children > .lil-gui').first())
    .locator('.lil-controller')
    .filter({ has: page.locator('.lil-name', { hasText: new RegExp(`^${label.replace(/[()]/g, '\\$&')}$`) }) });
const t0 = Date.now();
const mark = (what: string) => console.log(`${((Date.now() - t0) / 1000).toFixed(1)} s: ${what}`);

/** Waits until the render has stopped at STOP_AT spp with the latest meshes. */
async function renderDone(page: Page): Promise<void> {
  await page.waitForFunction((n) => document.body.dataset.render === 'done' && document.body.dataset.meshes === 'ready' && Number(document.querySelector('[data-testid="spp"]')?.textContent) === n, STOP_AT, { timeout: 120_000 });
}

/** Drops a file on an element, as a user dragging it from the desktop does. */
async function dropFile(target: Locator, name: string, bytes: Buffer): Promise<void> {
  await target.evaluate((element, file) => {
    const transfer = new DataTransfer();
    transfer.items.add(new File([new Uint8Array(file.bytes)], file.name, { type: 'image/png' }));
    for (const type of ['dragenter', 'dragover', 'drop']) element.dispatchEvent(new DragEvent(type, { dataTransfer: transfer, bubbles: true, cancelable: true }));
  }, { name, bytes: [...bytes] });
}

async function selectCentreMesh(page: Page): Promise<void> {
  const centre = await canvasPoint(page, 0.5, 0.5);
  await page.mouse.click(centre.x, centre.y);
  await page.locator('.lil-title', { hasText: 'Selected mesh 1' }).waitFor();
}

describe('texture slots on the page', () => {
  const harness = usePageHarness();

  it('opens the textured example; sets, keeps, rejects and clears a texture', async () => {
    const { page, errors } = await openPage(harness(), { minSpp: 1 });
    // The textured program takes SwiftShader a long time to compile on a loaded machine (the page is blocked meanwhile).
    page.setDefaultTimeout(120_000);
    const stop = control(page, 'stop at spp (0 = never)', true).locator('input');
    await stop.fill(String(STOP_AT));
    await stop.press('Enter');
    mark('opened');
    const seedPixels = (await canvasPixels(page)).rgba;

    // The example: its images and model come with it; it renders.
    await page.selectOption('#examples', 'textured');
    await expect.poll(async () => (await meshesOf(page)).map((m) => m.file), { timeout: 30_000 }).toEqual(['uvbox.obj', 'uvbox.obj']);
    mark('example loaded');
    await selectCentreMesh(page);
    await renderDone(page);
    mark('example rendered');
    expect(await page.getByTestId('error').isHidden()).toBe(true);
    const example = (await canvasPixels(page)).rgba;
    expect(meanAbsDifference(example, seedPixels)).toBeGreaterThan(5);
    // The box's base color is the grid image: a slot with its name and size; its roughness a constant.
    expect(await control(page, 'base color').locator('input').inputValue()).toBe('grid.png, 128×128');
    expect(await control(page, 'roughness').locator('input').first().inputValue()).toBe('0.35');
    // The ground's textured color and roughness: slots too.
    const ground = page.locator('.lil-gui').filter({ has: page.locator('> .lil-title', { hasText: /^Ground$/ }) });
    const groundSlot = (label: string) => ground.locator('.lil-controller').filter({ has: page.locator('.lil-name', { hasText: new RegExp(`^${label}$`) }) }).locator('input');
    expect([await groundSlot('color').inputValue(), await groundSlot('roughness').inputValue()]).toEqual(['checker.png, 256×256', 'rough.png, 128×128']);

    // A PNG dropped on the roughness: a texture of it, one undoable edit; the render changes.
    let restarts = await watchRestarts(page);
    await dropFile(control(page, 'roughness'), 'checker.png', readFileSync(CHECKER));
    await control(page, 'roughness').locator('.texture-button', { hasText: 'clear' }).waitFor();
    expect(await control(page, 'roughness').locator('input').inputValue()).toBe('checker.png, 256×256');
    expect((await meshesOf(page))[0].material.roughness).toEqual({ image: 'checker.png', channel: 'r', scale: 1, uv: { offset: [0, 0], scale: [1, 1], rotation: 0 } });
    await waitForRestart(restarts);
    await renderDone(page);
    mark('texture rendered');
    const textured = (await canvasPixels(page)).rgba;
    const texturedMaterial = (await meshesOf(page))[0].material;
    const change = meanAbsDifference(textured, example);
    expect(change).toBeGreaterThan(0.5);

    // A corrupt PNG opened on the base color's slot: rejected naming the key; scene and samples stay.
    restarts = await watchRestarts(page);
    const [chooser] = await Promise.all([page.waitForEvent('filechooser'), control(page, 'base color').locator('.texture-button', { hasText: 'image…' }).click()]);
    await chooser.setFiles({ name: 'broken.png', mimeType: 'image/png', buffer: readFileSync(CHECKER).subarray(0, 120) });
    const alert = page.getByTestId('error');
    await alert.waitFor({ state: 'visible' });
    expect(await alert.textContent()).toMatch(/The image "broken\.png" could not be used; the scene is unchanged\..*meshes\[0\]\.material\.baseColor\.image: "broken\.png"/);
    expect((await meshesOf(page))[0].material).toEqual(texturedMaterial);
    expect(await restarts()).toBe(0);
    expect(await spp(page)).toBe(STOP_AT);
    await alert.locator('.dismiss').click(); // it floats over the image

    // Clear: the constant roughness again, and the example's very pixels.
    restarts = await watchRestarts(page);
    await control(page, 'roughness').locator('.texture-button', { hasText: 'clear' }).click();
    await control(page, 'roughness').locator('input[type=number], input').first().waitFor();
    expect((await meshesOf(page))[0].material.roughness).toBe(0.35);
    await waitForRestart(restarts);
    await renderDone(page);
    mark('cleared');
    const cleared = meanAbsDifference((await canvasPixels(page)).rgba, example);
    console.log(`mean |difference| of the 8-bit image: roughness texture ${change.toFixed(2)}, cleared again ${cleared.toFixed(3)}`);
    expect(cleared).toBeLessThan(0.05 * change);

    // Undo: the texture again. Its image is kept with the autosave (restoring it: test/unit/autosave-images.test.ts).
    await page.click('#undo');
    await control(page, 'roughness').locator('.texture-button', { hasText: 'clear' }).waitFor();
    await page.waitForFunction(() => document.body.dataset.saved === 'saved');
    const kept = await page.evaluate(() => new Promise<{ names: string[]; scene: { meshes: SavedMesh[] } }>((resolve, reject) => {
      const open = indexedDB.open('pathtrace');
      open.onerror = () => reject(open.error);
      open.onsuccess = () => {
        const store = open.result.transaction('keyval').objectStore('keyval');
        const keys = store.getAllKeys();
        const state = store.get('autosave');
        keys.onsuccess = () => (state.onsuccess = () => resolve({ names: (keys.result as string[]).filter((k) => k.startsWith('asset:')), scene: JSON.parse(state.result).scene }));
      };
    }));
    expect(kept.names.sort()).toEqual(['asset:bumps.png', 'asset:checker.png', 'asset:grid.png', 'asset:rough.png', 'asset:uvbox.obj']);
    expect(kept.scene.meshes[0].material.roughness).toMatchObject({ image: 'checker.png' });
    expect(errors).toEqual([]);
    await page.close();
  }, 300_000);
});
