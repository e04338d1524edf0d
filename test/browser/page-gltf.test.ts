/**
 * A glTF dropped on the page with its files, end to end in headless
 * Chromium: a .gltf, its .bin and two PNG images (made here with
 * glTF-Transform and pngjs: two quads side by side, the left one's
 * baseColor a red image, the right one's a blue image) dropped together are
 * added as a mesh wearing the file's own materials (`material` absent,
 * version 3); the image shows red on the left and blue on the right; the
 * panel lists the materials, and switches to one material and back (undoable);
 * without its .bin the model is refused naming `meshes[0].file` and the .bin;
 * an extension it ignores is a notice; the share notice names all four files; the
 * .bin and the images are kept with the autosave, so a reload shows them
 * again. The scene is a link's: a white sky, no ground, nothing else, so
 * the colours seen are the textures'.
 */
import { compressToEncodedURIComponent } from 'lz-string';
import type { Page } from 'playwright-core';
import { describe, expect, it } from 'vitest';
import { quadsGltf } from '../support/gltfQuads';
import { canvasPixels, openPage, savedScene, usePageHarness, waitForSpp } from '../support/page';

const SCENE = {
  version: 3,
  camera: { position: [0, 0, 4], target: [0, 0, 0], fov: 40 },
  image: { width: 160, height: 100 },
  render: { maxBounces: 2 },
  environment: { color: [1, 1, 1], intensity: 1 },
  spheres: [],
};

/** Drops files on the page together, as a user dragging them from the desktop does. */
async function dropFiles(page: Page, files: Record<string, Uint8Array>): Promise<void> {
  const list = Object.entries(files).map(([name, bytes]) => ({ name, bytes: [...bytes] }));
  await page.evaluate((list) => {
    const transfer = new DataTransfer();
    for (const file of list) transfer.items.add(new File([new Uint8Array(file.bytes)], file.name));
    for (const type of ['dragenter', 'dragover', 'drop']) document.body.dispatchEvent(new DragEvent(type, { dataTransfer: transfer, bubbles: true, cancelable: true }));
  }, list);
}

/** The mean colour of the middle rows left and right of the centre, where the framed quads are. */
async function sideColours(page: Page): Promise<{ left: number[]; right: number[] }> {
  const { width, height, rgba } = await canvasPixels(page);
  const mean = (x0: number, x1: number) => {
    const sum = [0, 0, 0];
    let n = 0;
    for (let y = Math.floor(height * 0.42); y < height * 0.58; y++) {
      for (let x = Math.floor(x0); x < x1; x++, n++) for (let c = 0; c < 3; c++) sum[c] += rgba[4 * (y * width + x) + c];
    }
    return sum.map((s) => s / n);
  };
  return { left: mean(width * 0.32, width * 0.45), right: mean(width * 0.55, width * 0.68) };
}

/** Red where the red-textured quad is, blue where the blue one is (8-bit displayed values). */
function expectTextures(colours: { left: number[]; right: number[] }): void {
  console.log(`mean colours: left ${colours.left.map((c) => c.toFixed(0))}, right ${colours.right.map((c) => c.toFixed(0))}`);
  const [lr, lg, lb] = colours.left;
  const [rr, rg, rb] = colours.right;
  expect(lr).toBeGreaterThan(3 * Math.max(lg, lb) + 20);
  expect(rb).toBeGreaterThan(3 * Math.max(rr, rg) + 20);
}

async function renderedMeshes(page: Page, minSpp: number): Promise<void> {
  await page.waitForFunction(() => document.body.dataset.meshes === 'ready', undefined, { timeout: 120_000 });
  await waitForSpp(page, minSpp, 120_000);
}

describe('glTF files on the page', () => {
  const harness = usePageHarness();

  it('adds a dropped .gltf with its .bin and images wearing its materials, and keeps them', async () => {
    const hash = `#scene=${compressToEncodedURIComponent(JSON.stringify(SCENE))}`;
    const { page, errors } = await openPage(harness(), { hash, minSpp: 1 });
    page.setDefaultTimeout(120_000);
    const white = await sideColours(page);
    expect(Math.min(...white.left, ...white.right)).toBeGreaterThan(150); // the sky alone

    // Without its .bin: refused, naming the key and the missing file; the scene and its samples stay.
    const files = await quadsGltf();
    // An extension the loader ignores: a notice, not an error.
    const json = JSON.parse(new TextDecoder().decode(files['quads.gltf']));
    files['quads.gltf'] = new TextEncoder().encode(JSON.stringify({ ...json, extensionsUsed: ['EXT_page_test'] }));
    const { 'quads.bin': _bin, ...withoutBin } = files;
    await dropFiles(page, withoutBin);
    const alert = page.getByTestId('error');
    await alert.waitFor({ state: 'visible' });
    expect(await alert.textContent()).toMatch(/The model "quads\.gltf" could not be added; the scene is unchanged\..*meshes\[0\]\.file: "quads\.gltf": .*"quads\.bin"/);
    expect((await savedScene(page)).meshes ?? []).toEqual([]);
    await alert.locator('.dismiss').click();

    await dropFiles(page, files);
    await page.locator('.lil-title', { hasText: 'Selected mesh 1' }).waitFor();
    expect(await page.locator('#notice').textContent()).toBe('meshes[0].file: "quads.gltf" ignores the glTF extensions EXT_page_test');
    expect(await page.getByTestId('error').isHidden()).toBe(true);
    const scene = await savedScene(page);
    expect(scene.version).toBe(3);
    expect(scene.meshes).toHaveLength(1);
    expect((scene.meshes as Record<string, unknown>[])[0].file).toBe('quads.gltf');
    expect((scene.meshes as Record<string, unknown>[])[0]).not.toHaveProperty('material');
    // The panel lists the file's materials and the textures they use.
    const selection = page.locator('.lil-root > .lil-children > .lil-gui').first();
    const shown = async (label: string) => selection.locator('.lil-controller').filter({ has: page.locator('.lil-name', { hasText: new RegExp(`^${label}$`) }) }).locator('input').inputValue();
    expect([await shown('left'), await shown('right')]).toEqual(['baseColor: red.png', 'baseColor: blue.png']);
    expect(await selection.textContent()).toContain('one material for all');
    await renderedMeshes(page, 4);
    expectTextures(await sideColours(page));
    expect(await page.getByTestId('error').isHidden()).toBe(true);

    // "one material for all": a principled material, edited as any; "the file's materials": back; both undoable.
    const meshMaterial = async () => ((await savedScene(page)).meshes as Record<string, unknown>[])[0].material as Record<string, unknown> | undefined;
    await selection.locator('.lil-controller', { hasText: 'one material for all' }).locator('button').click();
    await selection.locator('.lil-controller', { hasText: "the file's materials" }).waitFor();
    expect((await meshMaterial())?.type).toBe('principled');
    await selection.locator('.lil-controller', { hasText: "the file's materials" }).locator('button').click();
    await selection.locator('.lil-controller', { hasText: 'one material for all' }).waitFor();
    expect(await meshMaterial()).toBeUndefined();
    await page.click('#undo');
    await selection.locator('.lil-controller', { hasText: "the file's materials" }).waitFor();
    await page.click('#redo');
    await selection.locator('.lil-controller', { hasText: 'one material for all' }).waitFor();
    // The share link cannot carry the user's files: its notice names them all.
    await page.click('#share');
    await expect.poll(() => page.locator('#notice').textContent()).toMatch(/It names your files "quads\.gltf", "quads\.bin", "red\.png", "blue\.png"/);

    // Kept with the autosave (the .bin and the images beside the .gltf too): a reload shows the textures again.
    await page.waitForFunction(() => document.body.dataset.saved === 'saved');
    const kept = await page.evaluate(() => new Promise<string[]>((resolve, reject) => {
      const open = indexedDB.open('pathtrace');
      open.onerror = () => reject(open.error);
      open.onsuccess = () => {
        const keys = open.result.transaction('keyval').objectStore('keyval').getAllKeys();
        keys.onsuccess = () => resolve((keys.result as string[]).filter((k) => k.startsWith('asset:')));
      };
    }));
    expect(kept.sort()).toEqual(['asset:blue.png', 'asset:quads.bin', 'asset:quads.gltf', 'asset:red.png']);
    await page.reload();
    await renderedMeshes(page, 4);
    expect(((await savedScene(page)).meshes as unknown[]).length).toBe(1);
    expectTextures(await sideColours(page));
    expect(errors).toEqual([]);
    await page.close();
  }, 300_000);
});
