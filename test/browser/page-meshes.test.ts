/**
 * Meshes on the page, end to end in headless Chromium: a model file opened
 * is added as a fitted mesh and framed; a click at the image centre selects
 * it; a drag moves it over its ground plane; the panel edits its material;
 * Delete removes it and Ctrl+Z brings it back; a corrupt model changes
 * nothing and names `meshes[i].file`; a big model opened twice is stored
 * once, so moving one of its meshes needs no BVH build; the bundled bunny
 * example renders.
 */
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import type { Page } from 'playwright-core';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { bumpySpherePly } from '../../bench/meshGen';
import { decodeMesh } from '../../src/scene/mesh';
import { meshBounds } from '../../src/scene/picking';
import { canvasPixels, canvasPoint, drag, meanAbsDifference, openPage, savedScene, spp, waitForRestart, waitForSpp, watchRestarts, usePageHarness } from '../support/page';

const ICO = fileURLToPath(new URL('../fixtures/meshes/ico-smooth.obj', import.meta.url));
const DRACO = fileURLToPath(new URL('../fixtures/meshes/ico-smooth-draco.glb', import.meta.url));

type SavedMesh = { file: string; position: number[]; rotation: number[]; scale: number | number[]; material: Record<string, unknown> };
const meshesOf = async (page: Page) => ((await savedScene(page)).meshes ?? []) as SavedMesh[];
const selectionTitle = (page: Page) => page.locator('.lil-root > .lil-children > .lil-gui > .lil-title').first().textContent();

const harness = usePageHarness();

describe('meshes on the page', () => {
  it('adds, picks, moves, edits, deletes and restores a model; rejects a corrupt one', async () => {
    const { page, errors } = await openPage(harness(), { minSpp: 2 });
    const before = await savedScene(page);
    const pixelsBefore = await canvasPixels(page);

    await page.setInputFiles('#file', ICO);
    await page.waitForFunction(() => /Selected mesh 1/.test(document.querySelector('.lil-root .lil-title + .lil-children')?.parentElement?.textContent ?? ''));
    let meshes = await meshesOf(page);
    expect(meshes).toHaveLength(1);
    expect(meshes[0].file).toBe('ico-smooth.obj');
    const saved = await savedScene(page);
    expect(saved.version).toBe(2);
    // Fitted: the unit icosphere (radius 1) stands on the ground (y = 0 in the seed scene) under the old target.
    const scale = Array.isArray(meshes[0].scale) ? meshes[0].scale[0] : meshes[0].scale;
    const { min } = meshBounds(await decodeMesh(new Uint8Array(readFileSync(ICO)), 'ico-smooth.obj'));
    expect(meshes[0].rotation).toEqual([0, 0, 0]);
    expect(meshes[0].position[1]).toBeCloseTo(-scale * min[1], 4);
    expect(saved.camera).not.toEqual(before.camera);
    // The BVH is built in the worker, then the scene with the mesh is uploaded.
    await page.waitForFunction(() => document.body.dataset.meshes === 'ready');
    await waitForSpp(page, 2);
    expect(meanAbsDifference((await canvasPixels(page)).rgba, pixelsBefore.rgba)).toBeGreaterThan(2);

    // Deselect, then a click at the centre of the framed view picks the mesh.
    await page.keyboard.press('Escape');
    expect(await selectionTitle(page)).not.toMatch(/mesh/);
    const centre = await canvasPoint(page, 0.5, 0.5);
    await page.mouse.click(centre.x, centre.y);
    expect(await selectionTitle(page)).toMatch(/Selected mesh 1/);
    const icoTriangles = (await decodeMesh(new Uint8Array(readFileSync(ICO)), 'ico-smooth.obj')).indices.length / 3;
    const trianglesField = page.locator('.lil-controller').filter({ has: page.locator('.lil-name', { hasText: /^triangles$/ }) }).locator('input');
    expect(await trianglesField.inputValue(), 'the panel tells the triangle count').toBe(icoTriangles.toLocaleString('en-US'));
    const storedField = page.locator('.lil-controller').filter({ has: page.locator('.lil-name', { hasText: /^stored$/ }) }).locator('input');
    expect(await storedField.inputValue()).toBe('a copy of its own');

    // Drag it sideways: it moves over the horizontal plane (x changes, y does not).
    await drag(page, centre, 40, 0);
    meshes = await meshesOf(page);
    expect(Math.abs(meshes[0].position[0])).toBeGreaterThan(0.05);
    await page.waitForFunction(() => document.body.dataset.meshes === 'ready');
    expect(meshes[0].position[1]).toBeCloseTo(-scale * min[1], 4);

    // The material through the panel.
    const roughness = page.locator('.lil-controller').filter({ has: page.locator('.lil-name', { hasText: /^roughness$/ }) }).first().locator('input').first();
    await roughness.fill('0.2');
    await roughness.press('Enter');
    await roughness.blur();
    expect((await meshesOf(page))[0].material.roughness).toBeCloseTo(0.2, 5);

    // Delete, then undo. The mesh is really drawn: the image without it differs.
    await page.waitForFunction(() => document.body.dataset.meshes === 'ready');
    await waitForSpp(page, 2);
    await page.keyboard.press('Escape'); // no selection outline in the screenshots
    const withMesh = await canvasPixels(page);
    await page.mouse.click(centre.x + 40, centre.y);
    const restarts = await watchRestarts(page);
    await page.keyboard.press('Delete');
    expect(await meshesOf(page)).toHaveLength(0);
    await waitForRestart(restarts);
    await waitForSpp(page, 2);
    expect(meanAbsDifference((await canvasPixels(page)).rgba, withMesh.rgba)).toBeGreaterThan(2);
    await page.keyboard.press('Control+z');
    expect(await meshesOf(page)).toHaveLength(1);

    // A corrupt model: an error naming meshes[1].file, and nothing changes.
    const unchanged = await savedScene(page);
    const sppBefore = await spp(page);
    await page.setInputFiles('#file', { name: 'broken.ply', mimeType: 'application/octet-stream', buffer: Buffer.from('ply\nformat ascii 1.0\nelement vertex 3\nend_header\n1 2\n') });
    const alert = page.getByTestId('error');
    await alert.waitFor({ state: 'visible' });
    expect(await alert.textContent()).toMatch(/meshes\[1\]\.file: "broken\.ply"/);
    expect(await savedScene(page)).toEqual(unchanged);
    expect(await spp(page)).toBeGreaterThanOrEqual(sppBefore); // accumulation was not restarted
    expect(errors).toEqual([]);
    await page.close();
  }, 180_000);

  it('a model opened twice is stored once: moving one of its meshes builds no new BVH', async () => {
    // 120k triangles: a second mesh of it would add enough to be instanced (src/render/bvh/groups.ts).
    const file = join(mkdtempSync(join(tmpdir(), 'instanced-')), 'sphere.ply');
    writeFileSync(file, bumpySpherePly(120_000));
    const { page, errors } = await openPage(harness(), { minSpp: 1 });
    for (let n = 1; n <= 2; n++) {
      await page.setInputFiles('#file', file);
      await page.waitForFunction((count) => document.body.dataset.meshes === 'ready' && (document.body.dataset.meshBuildMs ?? '') !== '' && document.querySelectorAll('.lil-root').length > 0 && new RegExp(`Selected mesh ${count}`).test(document.body.textContent ?? ''), n);
    }
    const meshes = await meshesOf(page);
    expect(meshes.map((m) => m.file)).toEqual(['sphere.ply', 'sphere.ply']);
    const storedField = page.locator('.lil-controller').filter({ has: page.locator('.lil-name', { hasText: /^stored$/ }) }).locator('input');
    expect(await storedField.inputValue(), 'the panel tells how the mesh is stored').toBe('once, for meshes 1, 2');
    await waitForSpp(page, 1);
    // A sentinel the page overwrites only when the BVH worker finishes a build.
    await page.evaluate(() => (document.body.dataset.meshBuildMs = 'none'));
    const restarts = await watchRestarts(page);
    const centre = await canvasPoint(page, 0.5, 0.5);
    await page.mouse.click(centre.x, centre.y);
    expect(await selectionTitle(page)).toMatch(/Selected mesh/);
    await drag(page, centre, 60, 0);
    const moved = await meshesOf(page);
    expect(moved[0].position.concat(moved[1].position)).not.toEqual(meshes[0].position.concat(meshes[1].position));
    await waitForRestart(restarts);
    await waitForSpp(page, 1);
    expect(await page.evaluate(() => document.body.dataset.meshBuildMs), 'no BVH was built for the move').toBe('none');
    expect(await page.evaluate(() => document.body.dataset.meshes)).toBe('ready');
    expect(errors).toEqual([]);
    await page.close();
  }, 180_000);

  it('opens a Draco-compressed glTF: the page decodes it in its worker (the page itself allows no WebAssembly)', async () => {
    const { page, errors } = await openPage(harness(), { minSpp: 1 });
    await page.setInputFiles('#file', DRACO);
    await expect.poll(async () => (await meshesOf(page)).map((m) => m.file), { timeout: 30_000 }).toEqual(['ico-smooth-draco.glb']);
    await page.waitForFunction(() => document.body.dataset.meshes === 'ready');
    expect(await page.getByTestId('error').isHidden()).toBe(true);
    expect(errors).toEqual([]);
    await page.close();
  }, 120_000);

  it('opens the bundled bunny example, adds a model to it, and both come back after a reload', async () => {
    const { page, errors } = await openPage(harness(), { minSpp: 1 });
    const pixelsBefore = await canvasPixels(page);
    await page.selectOption('#examples', 'bunny (model)');
    await expect.poll(async () => (await meshesOf(page)).map((m) => m.file), { timeout: 30_000 }).toEqual(['bunny.ply']);
    await page.waitForFunction(() => document.body.dataset.meshes === 'ready');
    await waitForSpp(page, 2);
    expect(meanAbsDifference((await canvasPixels(page)).rgba, pixelsBefore.rgba)).toBeGreaterThan(2);
    await page.setInputFiles('#file', ICO);
    await expect.poll(async () => (await meshesOf(page)).map((m) => m.file), { timeout: 30_000 }).toEqual(['bunny.ply', 'ico-smooth.obj']);
    const scene = await savedScene(page);
    await page.waitForTimeout(1500); // the model file is kept first (IndexedDB), then the scene saved
    await page.waitForFunction(() => document.body.dataset.saved === 'saved');
    await page.reload();
    await waitForSpp(page, 1);
    expect(await savedScene(page)).toEqual(scene);
    await page.waitForFunction(() => document.body.dataset.meshes === 'ready');
    expect(await page.getByTestId('error').isHidden()).toBe(true);
    expect(errors).toEqual([]);
    await page.close();
  }, 120_000);
});
