/**
 * The page's material editing (scene format version 2), end to end in
 * headless Chromium: the selected sphere's material type, ior, tint and
 * emission through the panel, what "Save JSON" and the share link write,
 * undo/redo refreshing the panel, the glass and emissive examples, and the
 * shader programs the edits cost (WebGL linkProgram calls are counted).
 */
import type { Locator, Page } from 'playwright-core';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { hexToLinear } from '../../src/scene/color';
import { projectPoint } from '../../src/scene/picking';
import { defaultScene, PRESETS } from '../../src/scene/presets';
import { parseScene } from '../../src/scene/schema';
import { serializeScene } from '../../src/scene/serialize';
import { canvasPoint, drag, openPage, savedScene, spp, waitForSpp, usePageHarness, instrument, probe } from '../support/page';

const seed = defaultScene();
const seedJson = serializeScene(seed);


/** The longest gap between animation frames since `since` (ms, page clock). */
async function longestFrameGap(page: Page, since: number): Promise<number> {
  const frames = (await probe(page)).frames.filter((t) => t >= since);
  let gap = 0;
  for (let i = 1; i < frames.length; i++) gap = Math.max(gap, frames[i] - frames[i - 1]);
  return gap;
}

/** The selection folder (the panel's first folder). */
const selectionFolder = (page: Page) => page.locator('.lil-root > .lil-children > .lil-gui').first();

/** A controller of the selection folder by its exact label. */
function control(page: Page, name: string): Locator {
  return selectionFolder(page).locator('.lil-controller').filter({ has: page.locator('.lil-name', { hasText: new RegExp(`^${name}$`) }) });
}

/** The selection folder's rows: the object list ("object"), then the object's controls. */
async function labels(page: Page): Promise<string[]> {
  return selectionFolder(page).locator('.lil-controller .lil-name').allTextContents();
}

/** Types into a number or text field and leaves it (one finished edit). */
async function enter(field: Locator, value: string): Promise<void> {
  await field.fill(value);
  await field.press('Enter');
  await field.blur();
}

/** Switches the material type the way a user does; returns how long the page was blocked (ms). */
async function switchType(page: Page, type: string): Promise<number> {
  await control(page, 'material').locator('select').waitFor();
  return page.evaluate((to) => {
    const folder = document.querySelector('.lil-root > .lil-children > .lil-gui')!;
    const row = [...folder.querySelectorAll('.lil-controller')].find((c) => c.querySelector('.lil-name')?.textContent === 'material')!;
    const select = row.querySelector('select')!;
    const start = performance.now();
    select.selectedIndex = [...select.options].findIndex((o) => o.textContent === to);
    select.dispatchEvent(new Event('change'));
    return performance.now() - start;
  }, type);
}

/** Picks an option of the selection folder's `name` dropdown, as a user does. */
async function choose(page: Page, name: string, option: string): Promise<void> {
  const select = control(page, name).locator('select');
  await select.waitFor();
  await select.selectOption({ label: option });
}

/** The page's sRGB -> linear conversion may differ from Node's in the last bit (Math.pow). */
function expectColor(actual: unknown, hex: string): void {
  const expected = hexToLinear(hex);
  expect(actual).toHaveLength(3);
  (actual as number[]).forEach((c, i) => expect(c).toBeCloseTo(expected[i], 12));
}

type SavedSphere = { material: Record<string, unknown> };
const savedSpheres = async (page: Page) => (await savedScene(page)).spheres as SavedSphere[];

async function selectSphere(page: Page, index: number): Promise<void> {
  const p = projectPoint(seed.camera, seed.image.width / seed.image.height, seed.spheres[index].center)!;
  await drag(page, await canvasPoint(page, p.u, p.v), 0, 0);
  await selectionFolder(page).locator('.lil-title', { hasText: `Selected sphere ${index + 1}` }).waitFor();
}

describe('the page edits version-2 materials', () => {
  const harness = usePageHarness();

  it('switches a sphere to glass, sets ior and emission, saves version 2; undo restores the standard material', async () => {
    const { page, errors } = await openPage(harness(), { initScript: instrument });
    await selectSphere(page, 0);
    expect(await labels(page)).toEqual(['object', 'material', 'color', 'roughness', 'emission color', 'emission intensity', 'radius', 'Delete']);
    const linksBefore = (await probe(page)).links;
    const renderingSince = await page.evaluate(() => performance.now());
    await waitForSpp(page, (await spp(page)) + 3);
    const usualGapMs = await longestFrameGap(page, renderingSince);

    // Standard -> dielectric: clear glass, type-specific controls, one new program.
    const switchStart = await page.evaluate(() => performance.now());
    const blockedMs = await switchType(page, 'dielectric');
    await control(page, 'ior').waitFor();
    expect(await labels(page)).toEqual(['object', 'material', 'tint', 'roughness', 'ior', 'emission color', 'emission intensity', 'radius', 'Delete']);
    const sppAfterSwitch = await spp(page);
    await waitForSpp(page, sppAfterSwitch + 3);
    const freezeMs = await longestFrameGap(page, switchStart);
    console.log(`first glass: the change handler blocked ${blockedMs.toFixed(0)} ms (program compile and link); longest frame gap after it ${freezeMs.toFixed(0)} ms (before: ${usualGapMs.toFixed(0)} ms)`);
    expect((await probe(page)).links - linksBefore, 'the first glass costs one program').toBe(1);

    await enter(control(page, 'ior').locator('input'), '1.7');
    let spheres = await savedSpheres(page);
    const saved = await savedScene(page);
    expect(saved.version).toBe(2);
    expect(spheres[0].material).toEqual({ type: 'dielectric', color: [1, 1, 1], roughness: 0, ior: 1.7 });
    expect(spheres.slice(1)).toEqual(serializeScene({ ...seed, version: 2 }).spheres?.slice(1));

    // Tint and roughness of the glass: same program.
    await enter(control(page, 'tint').locator('input[type=text]'), '#80c0ff');
    await enter(control(page, 'roughness').locator('input'), '0.25');
    spheres = await savedSpheres(page);
    expect(spheres[0].material).toMatchObject({ type: 'dielectric', roughness: 0.25, ior: 1.7 });
    expectColor(spheres[0].material.color, '#80c0ff');
    expect((await probe(page)).links - linksBefore, 'edits within a feature set never compile').toBe(1);

    // Emission: intensity creates it, color sets it, 0 removes the key.
    await enter(control(page, 'emission intensity').locator('input'), '5');
    expect((await savedSpheres(page))[0].material.emission).toEqual({ color: [1, 1, 1], intensity: 5 });
    await enter(control(page, 'emission color').locator('input[type=text]'), '#ff8000');
    let emission = (await savedSpheres(page))[0].material.emission as { color: unknown; intensity: number };
    expect(emission.intensity).toBe(5);
    expectColor(emission.color, '#ff8000');
    await enter(control(page, 'emission intensity').locator('input'), '0');
    expect('emission' in (await savedSpheres(page))[0].material).toBe(false);
    // The color set aside comes back with the next intensity.
    await enter(control(page, 'emission intensity').locator('input'), '2');
    emission = (await savedSpheres(page))[0].material.emission as { color: unknown; intensity: number };
    expect(emission.intensity).toBe(2);
    expectColor(emission.color, '#ff8000');

    // Undo every step (type, ior, tint, roughness, 4 emission edits): the seed again, panel rebuilt.
    const linksBeforeUndo = (await probe(page)).links;
    for (let i = 0; i < 8; i++) await page.click('#undo');
    expect(await savedScene(page)).toEqual(seedJson);
    await control(page, 'color').waitFor();
    expect(await labels(page)).not.toContain('ior');
    expect(await control(page, 'material').locator('select').inputValue()).toBe('standard');
    expect(await control(page, 'roughness').locator('input').inputValue()).toBe(String(seed.spheres[0].material.roughness));
    // Redo the switch: glass again, from the cached program.
    const redoSince = await page.evaluate(() => performance.now());
    await page.click('#redo');
    await control(page, 'ior').waitFor();
    expect(await control(page, 'ior').locator('input').inputValue()).toBe('1.5');
    expect((await savedSpheres(page))[0].material).toEqual({ type: 'dielectric', color: [1, 1, 1], roughness: 0, ior: 1.5 });
    expect((await probe(page)).links - linksBeforeUndo, 'undo and redo reuse compiled programs').toBe(0);
    await waitForSpp(page, (await spp(page)) + 3);
    const cachedGapMs = await longestFrameGap(page, redoSince);
    console.log(`glass again (cached program): longest frame gap ${cachedGapMs.toFixed(0)} ms`);
    // Loose bounds (2 shared cores): the one compile is seconds at most on SwiftShader
    // (about 2 s measured, at first draw), a cached program is a usual frame (0.1-0.4 s).
    expect(freezeMs, 'the first glass freezes the page too long').toBeLessThan(15_000);
    expect(cachedGapMs, 'a cached glass program still froze the page').toBeLessThan(1_500);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('switching back to standard brings back the sphere\'s color and roughness; the scene is version 1 again', async () => {
    const { page, errors } = await openPage(harness());
    await selectSphere(page, 3);
    await switchType(page, 'dielectric');
    await control(page, 'ior').waitFor();
    await enter(control(page, 'ior').locator('input'), '2.4');
    await switchType(page, 'standard');
    await control(page, 'color').waitFor();
    expect(await savedScene(page)).toEqual(seedJson);
    // And to glass again: the ior set before comes back too.
    await switchType(page, 'dielectric');
    await control(page, 'ior').waitFor();
    expect((await savedSpheres(page))[3].material).toEqual({ type: 'dielectric', color: [1, 1, 1], roughness: 0, ior: 2.4 });
    expect(errors).toEqual([]);
    await page.close();
  });

  it('makes a sphere a metal from the picker, saves version 3, keeps eta and k as "custom"; back to standard is version 1', async () => {
    const { page, errors } = await openPage(harness());
    await selectSphere(page, 1);
    await switchType(page, 'conductor');
    await control(page, 'metal').waitFor();
    expect(await labels(page)).toEqual(['object', 'material', 'metal', 'tint', 'roughness', 'emission color', 'emission intensity', 'radius', 'Delete']);
    const saved = await savedScene(page);
    expect(saved.version).toBe(3);
    expect(((saved.spheres as SavedSphere[])[1]).material).toMatchObject({ type: 'conductor', metal: 'Al', color: [1, 1, 1] });
    await choose(page, 'metal', 'Au');
    expect((await savedSpheres(page))[1].material).toMatchObject({ type: 'conductor', metal: 'Au' });
    // "custom": the metal's eta and k, written out, editable in the file.
    await choose(page, 'metal', 'custom');
    const custom = (await savedSpheres(page))[1].material;
    expect(custom).not.toHaveProperty('metal');
    expect((custom.eta as number[])[0]).toBeCloseTo(0.143036, 5);
    expect((custom.k as number[])[0]).toBeCloseTo(3.982997, 5);
    await waitForSpp(page, (await spp(page)) + 2);
    await switchType(page, 'standard');
    await control(page, 'color').waitFor();
    expect(await savedScene(page)).toEqual(seedJson);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('shares a scene with glass and emission: the link opens the same version-2 scene', async () => {
    const { page, errors } = await openPage(harness());
    await selectSphere(page, 2);
    await switchType(page, 'dielectric');
    await control(page, 'ior').waitFor();
    await enter(control(page, 'emission intensity').locator('input'), '3');
    await page.click('#share');
    await page.waitForFunction(() => location.hash.startsWith('#scene='));
    const shared = await savedScene(page);
    expect(shared.version).toBe(2);
    expect((shared.spheres as SavedSphere[])[2].material).toEqual({
      type: 'dielectric', color: [1, 1, 1], roughness: 0, ior: 1.5, emission: { color: [1, 1, 1], intensity: 3 },
    });
    const opened = await openPage(harness(), { url: page.url() });
    expect(await savedScene(opened.page)).toEqual(shared);
    expect(await opened.page.getByTestId('error').isHidden()).toBe(true);
    expect([...errors, ...opened.errors]).toEqual([]);
    await Promise.all([page.close(), opened.page.close()]);
  });

  it('lists and loads the glass and emissive examples; the panel follows the loaded materials', async () => {
    const { page, errors } = await openPage(harness());
    const names = await page.locator('#examples option').allTextContents();
    expect(names).toEqual(expect.arrayContaining(['glass', 'emissive']));
    await selectSphere(page, 0);
    for (const name of ['glass', 'emissive']) {
      await page.selectOption('#examples', name);
      expect(await savedScene(page)).toEqual(serializeScene(parseScene(PRESETS[name])));
      const now = await spp(page);
      await waitForSpp(page, now + 2);
    }
    // The selection (sphere 1) survived both loads; its controls show the emissive example's material.
    const material = parseScene(PRESETS.emissive).spheres[0].material;
    expect(await control(page, 'material').locator('select').inputValue()).toBe('standard');
    expect(Number(await control(page, 'emission intensity').locator('input').inputValue())).toBe(material.emission!.intensity);
    await page.click('#undo'); // back to glass: its first sphere is smooth glass
    await control(page, 'ior').waitFor();
    expect(await control(page, 'material').locator('select').inputValue()).toBe('dielectric');
    expect(await labels(page)).toContain('tint');
    expect(errors).toEqual([]);
    await page.close();
  });
});
