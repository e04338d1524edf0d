/**
 * Frame times of the page (dist/web) in headless Chromium with a generated
 * ~1M-triangle mesh at a 512x384 render: the model is opened through the
 * page's file input as a user would, then every animation-frame gap is
 * recorded while it decodes, while its BVH is built in the worker, and for
 * `--seconds` of rendering afterwards; the seed scene without the mesh is
 * measured first for comparison. Prints the frame gaps' percentiles and
 * maximum, samples per second (with the fraction of the sample in progress,
 * where the page tells it) and the render loop's paths per frame. Run after
 * `npm run build:web`:
 *   npx tsx bench/mesh-page-frames.ts [--triangles 1000000 | --file model.glb] [--seconds 15] [--paused] [--timeline] [--web DIR] [--chrome-trace FILE]
 * (--timeline: lists each frame over 100 ms while rendering the mesh, with the frames around it.)
 * (--chrome-trace: a Chromium trace of 4 s of rendering the mesh, before the measured seconds: its GPU
 * process shows each compositor frame's SkiaOutputSurfaceImplOnGpu::SwapBuffers, which headless reads the
 * page back after all GPU work queued before it.)
 * (--web: another build's dist/web, to compare.)
 * (--paused: the render is paused while the model loads, to see the page's own work.)
 */
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import type { Page } from 'playwright-core';
import { launchChromium, webRoot } from '../src/node/session';
import { serveDirectory } from '../src/node/server';
import { bumpySpherePly } from './meshGen';

const option = (argv: string[], name: string, fallback: string) => {
  const i = argv.indexOf(`--${name}`);
  return i >= 0 && i + 1 < argv.length ? argv[i + 1] : fallback;
};

function recordFrames(): void {
  const w = window as unknown as { __frames: number[]; __paths: number[] };
  w.__frames = [];
  w.__paths = [];
  const tick = (t: number) => {
    w.__frames.push(t);
    // The paths the render loop chose in its last frame (this callback runs before the loop's).
    w.__paths.push(Number(document.body?.dataset.pathsPerFrame ?? 0));
    requestAnimationFrame(tick);
  };
  requestAnimationFrame(tick);
}

/** With --timeline: every frame over 100 ms in the window, with the paths per frame around it. */
async function longFrames(page: Page, from: number, to: number): Promise<string> {
  const { frames, paths } = await page.evaluate(() => {
    const w = window as unknown as { __frames: number[]; __paths: number[] };
    return { frames: w.__frames, paths: w.__paths };
  });
  const lines: string[] = [];
  for (let i = 1; i < frames.length; i++) {
    if (frames[i] < from || frames[i] > to || frames[i] - frames[i - 1] <= 100) continue;
    const around = frames.slice(Math.max(1, i - 4), i + 3).map((t, k) => {
      const j = Math.max(1, i - 4) + k;
      return `${(t - frames[j - 1]).toFixed(0)}ms/${paths[j]}`;
    });
    lines.push(`  t=${((frames[i] - from) / 1000).toFixed(2)} s: gap ${(frames[i] - frames[i - 1]).toFixed(0)} ms; gaps/paths around: ${around.join(' ')}`);
  }
  return lines.join('\n');
}

const now = (page: Page) => page.evaluate(() => performance.now());

async function gaps(page: Page, from: number, to: number): Promise<string> {
  const frames = await page.evaluate(() => (window as unknown as { __frames: number[] }).__frames);
  const inside = frames.filter((t) => t >= from && t <= to);
  const d = inside.slice(1).map((t, i) => t - inside[i]).sort((a, b) => a - b);
  if (!d.length) return 'no frames';
  const q = (p: number) => d[Math.min(d.length - 1, Math.floor(p * d.length))].toFixed(0);
  const over = d.filter((x) => x > 100).length;
  return `${d.length} frames, median ${q(0.5)} ms, p95 ${q(0.95)} ms, p99 ${q(0.99)} ms, max ${d[d.length - 1].toFixed(0)} ms, ${over} over 100 ms (${((100 * over) / d.length).toFixed(1)}%)`;
}

/** Samples per pixel the page has: complete ones plus the fraction of the one in progress where the page tells it. */
async function samples(page: Page): Promise<number> {
  return page.evaluate(() => Number(document.body.dataset.samples ?? document.querySelector('[data-testid="spp"]')?.textContent));
}

/** The paths per frame the render loop chose (pages built before it tell nothing). */
async function pathsPerFrame(page: Page): Promise<string> {
  const paths = await page.evaluate(() => document.body.dataset.pathsPerFrame);
  return paths ? `; ${paths} paths per frame` : '';
}

async function main(argv: string[]): Promise<void> {
  const triangles = Number(option(argv, 'triangles', '1000000'));
  const seconds = Number(option(argv, 'seconds', '15'));
  // --file: a model of one's own (bench.glb: its textures upload too), else the generated sphere.
  const given = option(argv, 'file', '');
  const ply = given ? readFileSync(given) : Buffer.from(bumpySpherePly(triangles));
  const file = given || join(mkdtempSync(join(tmpdir(), 'mesh-frames-')), `sphere-${triangles}.ply`);
  if (!given) writeFileSync(file, ply);
  const server = await serveDirectory(option(argv, 'web', webRoot()));
  const browser = await launchChromium();
  try {
    const page = await browser.newPage({ viewport: { width: 1400, height: 1000 }, deviceScaleFactor: 1 });
    await page.addInitScript({ content: 'globalThis.__name = (f) => f;' }); // tsx's keepNames helper
    await page.addInitScript(recordFrames);
    await page.goto(`${server.url}?maxwidth=512`);
    await page.waitForFunction(() => Number(document.querySelector('[data-testid="spp"]')?.textContent) >= 2, undefined, { timeout: 120_000 });
    const res = await page.locator('#resolution').textContent();
    let t0 = await now(page);
    let s0 = await samples(page);
    await page.waitForTimeout(seconds * 1000);
    let t1 = await now(page);
    const seedRate = ((await samples(page)) - s0) / ((t1 - t0) / 1000);
    console.log(`seed scene at ${res}: ${await gaps(page, t0, t1)}; ${seedRate.toFixed(2)} spp/s${await pathsPerFrame(page)}`);

    // Paused while the model loads: the frame gaps are then the page's own
    // work for the model (decode, fit, upload), not path tracing.
    const paused = argv.includes('--paused');
    if (paused) await page.click('#pause');
    t0 = await now(page);
    // From a file on disk: a buffer would be built into a File by script in the page, blocking it.
    await page.setInputFiles('#file', file);
    await page.waitForFunction(() => document.body.dataset.meshes === 'building', undefined, { timeout: 300_000 });
    t1 = await now(page);
    console.log(`opening the ${(ply.length / 2 ** 20).toFixed(1)} MB model until its BVH build starts: ${((t1 - t0) / 1000).toFixed(1)} s; ${await gaps(page, t0, t1)}`);
    await page.waitForFunction(() => document.body.dataset.meshes !== 'building', undefined, { timeout: 600_000 });
    if ((await page.evaluate(() => document.body.dataset.meshes)) !== 'ready') throw new Error(`the BVH build failed: ${await page.getByTestId('error').textContent()}`);
    const t2 = await now(page);
    const buildMs = await page.evaluate(() => document.body.dataset.meshBuildMs);
    console.log(`BVH build in the worker: ${((t2 - t1) / 1000).toFixed(1)} s (worker ${buildMs} ms); frames meanwhile: ${await gaps(page, t1, t2)}`);
    if (paused) {
      await page.waitForTimeout(2000); // the upload itself happens on the next frame
      console.log(`(paused) frames from the upload on: ${await gaps(page, t2, await now(page))}`);
      await page.click('#pause');
    }
    // A textured, normal-mapped model compiles a program of its own first (minutes on SwiftShader).
    await page.waitForFunction(() => Number(document.querySelector('[data-testid="spp"]')?.textContent) >= 1, undefined, { timeout: 900_000 });
    let t3 = await now(page);
    console.log(`first sample of the mesh after upload: ${((t3 - t2) / 1000).toFixed(1)} s; ${await gaps(page, t2, t3)}`);
    const chromeTrace = option(argv, 'chrome-trace', '');
    if (chromeTrace) {
      await browser.startTracing(page, { path: chromeTrace, categories: ['toplevel', 'gpu', 'gpu.angle', 'viz', 'cc', 'blink', 'devtools.timeline'] });
      await page.waitForTimeout(4000);
      await browser.stopTracing();
      t3 = await now(page); // the measured seconds start after the trace
    }
    s0 = await samples(page);
    await page.waitForTimeout(seconds * 1000);
    const t4 = await now(page);
    const s4 = await samples(page);
    const rate = (s4 - s0) / ((t4 - t3) / 1000);
    console.log(
      `rendering ${triangles} triangles at ${await page.locator('#resolution').textContent()}: ${await gaps(page, t3, t4)}; ` +
        `${s4.toFixed(2)} spp, ${rate.toFixed(3)} spp/s${await pathsPerFrame(page)}`,
    );
    if (argv.includes('--timeline')) console.log(await longFrames(page, t3, t4));
    // The floor: the same page with the render paused, so frame gaps are the
    // page's and the machine's own (a loaded machine stalls frames too).
    await page.click('#pause');
    await page.waitForTimeout(1000);
    const t5 = await now(page);
    await page.waitForTimeout(Math.min(seconds, 10) * 1000);
    console.log(`paused (no path tracing), for comparison: ${await gaps(page, t5, await now(page))}`);
  } finally {
    await browser.close();
    await server.close();
  }
}

main(process.argv.slice(2)).catch((error) => {
  console.error(error);
  process.exit(1);
});
