/**
 * A heavy mesh on the page: the render loop shrinks its work per frame to a
 * part of a sample (tiles, PathTracer.renderPaths), so frames keep coming
 * while a sample takes seconds. Generated sphere of 300k triangles at
 * 512x384: one sample over the image takes ~1.5 s on SwiftShader on the
 * 2-core reference machine (~8 us per path), which an untiled frame would
 * last at least. Asserted, with wide margins for a loaded machine:
 *  - the loop's paths per frame (body[data-paths-per-frame]) drop to under
 *    a quarter of a sample, and to under half of what the seed scene gets
 *    (its paths cost ~5x less);
 *  - samples still advance, fraction by fraction (body[data-samples]);
 *  - the median frame gap stays under 250 ms (measured: ~50 ms, and ~50 ms
 *    with the render paused on a machine loaded by other jobs; an untiled
 *    frame is >= 1.5 s). The 100 ms target itself is measured by
 *    bench/mesh-page-frames.ts, not asserted here.
 */
import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import type { Page } from 'playwright-core';
import { describe, expect, it } from 'vitest';
import { bumpySpherePly } from '../../bench/meshGen';
import { instrument, openPage, probe, usePageHarness } from '../support/page';

const harness = usePageHarness();

const pathsPerFrame = (page: Page) => page.evaluate(() => Number(document.body.dataset.pathsPerFrame));
const samples = (page: Page) => page.evaluate(() => Number(document.body.dataset.samples));

describe('a heavy mesh on the page', () => {
  it('renders in parts of a sample per frame, frames keep coming', async () => {
    const file = join(mkdtempSync(join(tmpdir(), 'heavy-mesh-')), 'sphere.ply');
    writeFileSync(file, bumpySpherePly(300_000));
    const { page, errors } = await openPage(harness(), { maxWidth: 512, viewport: { width: 1200, height: 900 }, initScript: instrument });
    const [width, height] = (await page.locator('#resolution').textContent())!.split('×').map(Number);
    expect(width).toBe(512);
    const pixels = width * height;
    await page.waitForTimeout(1500); // the budget settles on the seed scene
    const seedPaths = await pathsPerFrame(page);
    expect(seedPaths).toBeGreaterThan(0);

    await page.setInputFiles('#file', file);
    await page.waitForFunction(() => document.body.dataset.meshes === 'building', undefined, { timeout: 60_000 });
    await page.waitForFunction(() => document.body.dataset.meshes === 'ready', undefined, { timeout: 60_000 });
    await page.waitForTimeout(3000); // the upload (and the mesh program's compile), then the budget settles

    const start = await page.evaluate(() => performance.now());
    const before = await samples(page);
    await page.waitForTimeout(6000);
    const end = await page.evaluate(() => performance.now());
    const after = await samples(page);
    const meshPaths = await pathsPerFrame(page);
    const frames = (await probe(page)).frames.filter((t) => t >= start && t <= end);
    const gaps = frames.slice(1).map((t, i) => t - frames[i]).sort((a, b) => a - b);
    const median = gaps[Math.floor(gaps.length / 2)];
    const detail = `paths per frame: seed ${seedPaths}, mesh ${meshPaths} of ${pixels} pixels; ${gaps.length} frames, median gap ${median?.toFixed(0)} ms; samples ${before} -> ${after}`;

    expect(meshPaths, detail).toBeLessThan(pixels / 4);
    expect(meshPaths, detail).toBeLessThan(seedPaths / 2);
    expect(after - before, detail).toBeGreaterThan(0.05);
    expect(gaps.length, detail).toBeGreaterThan(10);
    expect(median, detail).toBeLessThan(250);
    expect(errors).toEqual([]);
    await page.close();
  });
});
