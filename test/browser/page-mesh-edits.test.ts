/**
 * Scene edits around a big mesh on the page build no new BVH: triangles
 * carry their mesh (and a mesh-local material index), the mesh record its
 * first global material slot (src/render/bvh/pack.ts, layout/scene.ts MESH),
 * so adding a sphere or a light, toggling the ground (each shifts the
 * meshes' global material slots) or editing the mesh's material, emission
 * included, leaves the BVH as built. Counted two ways: the BVH worker's
 * builds (each writes body[data-mesh-build-ms]) and the uploads of a BVH
 * texture (WebGL texStorage3D: only the BVH is a 2D array texture on the
 * page), which also catches a build on the page's own thread.
 */
import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import type { Locator, Page } from 'playwright-core';
import { describe, expect, it } from 'vitest';
import { bumpySpherePly } from '../../bench/meshGen';
import { openPage, savedScene, usePageHarness, waitForRestart, waitForSpp, watchRestarts } from '../support/page';

const harness = usePageHarness();

/** Counts BVH texture allocations (texStorage3D of a 2D array texture) in window.__bvhUploads. */
function countBvhUploads(): void {
  const w = window as unknown as { __bvhUploads: number };
  w.__bvhUploads = 0;
  const storage = WebGL2RenderingContext.prototype.texStorage3D;
  WebGL2RenderingContext.prototype.texStorage3D = function (this: WebGL2RenderingContext, ...args: Parameters<WebGL2RenderingContext['texStorage3D']>) {
    if (args[0] === this.TEXTURE_2D_ARRAY) w.__bvhUploads += 1;
    return storage.apply(this, args);
  };
}

const counts = (page: Page) =>
  page.evaluate(() => {
    const w = window as unknown as { __bvhUploads: number; __bvhBuilds: number };
    return { builds: w.__bvhBuilds, uploads: w.__bvhUploads };
  });

/** A controller of the selection folder (the panel's first) by its exact label. */
const control = (page: Page, name: string): Locator =>
  page.locator('.lil-root > .lil-children > .lil-gui').first().locator('.lil-controller').filter({ has: page.locator('.lil-name', { hasText: new RegExp(`^${name}$`) }) });

async function enter(field: Locator, value: string): Promise<void> {
  await field.fill(value);
  await field.press('Enter');
  await field.blur();
}

/** Runs `edit`, then waits until the page shows its result (the accumulation restarted, the meshes ready). */
async function edited(page: Page, edit: () => Promise<void>): Promise<void> {
  const restarts = await watchRestarts(page);
  await edit();
  await waitForRestart(restarts, 60_000);
  await page.waitForFunction(() => document.body.dataset.meshes === 'ready', undefined, { timeout: 60_000 });
  await waitForSpp(page, 1);
}

describe('scene edits around a big mesh', () => {
  it('adding a sphere and a light, toggling the ground and editing materials build no BVH after the first', async () => {
    const file = join(mkdtempSync(join(tmpdir(), 'mesh-edits-')), 'sphere.ply');
    writeFileSync(file, bumpySpherePly(200_000));
    const { page, errors } = await openPage(harness(), { minSpp: 1, initScript: countBvhUploads });
    await page.evaluate(() => {
      const w = window as unknown as { __bvhBuilds: number };
      w.__bvhBuilds = 0;
      new MutationObserver((records) => (w.__bvhBuilds += records.length)).observe(document.body, { attributes: true, attributeFilter: ['data-mesh-build-ms'] });
    });

    await page.setInputFiles('#file', file);
    await page.waitForFunction(() => document.body.dataset.meshes === 'ready' && (document.body.dataset.meshBuildMs ?? '') !== '' && /Selected mesh 1/.test(document.body.textContent ?? ''), undefined, { timeout: 120_000 });
    await waitForSpp(page, 1);
    expect(await counts(page), 'the model: one build, one upload').toEqual({ builds: 1, uploads: 1 });

    // The mesh (selected) gets another roughness, then emission: its emissive-triangle table is made, not its BVH.
    await edited(page, () => enter(control(page, 'roughness').locator('input'), '0.3'));
    await edited(page, () => enter(control(page, 'emission intensity').locator('input'), '2'));
    await edited(page, () => page.click('#add-sphere'));
    await edited(page, () => enter(control(page, 'roughness').locator('input'), '0.1')); // the new sphere's
    await edited(page, () => page.click('#add-light'));
    await edited(page, async () => {
      const ground = page.locator('.lil-root > .lil-children > .lil-gui').filter({ has: page.locator('> .lil-title', { hasText: /^Ground$/ }) });
      await ground.locator('> .lil-title').click();
      await ground.locator('.lil-controller', { has: page.locator('.lil-name', { hasText: /^enabled$/ }) }).locator('input').click();
    });

    const scene = await savedScene(page);
    expect(scene.ground ?? null, "the ground is off").toBeNull();
    expect((scene.spheres as unknown[]).length).toBeGreaterThan(0);
    expect((scene.lights as unknown[]).length).toBeGreaterThan(0);
    const meshes = scene.meshes as { material: { roughness: number; emission?: { intensity: number } } }[];
    expect(meshes[0].material.roughness).toBeCloseTo(0.3, 5);
    expect(meshes[0].material.emission?.intensity).toBe(2);
    await page.waitForTimeout(1000); // a late build would show here
    expect(await counts(page), 'after the edits: still the first build and upload only').toEqual({ builds: 1, uploads: 1 });
    expect(errors).toEqual([]);
    await page.close();
  }, 300_000);
});
