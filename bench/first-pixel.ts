/**
 * Time to first pixel of the page: from navigation start to the first frame
 * with a rendered sample on the canvas (the page's `first-pixel` performance
 * mark), in headless Chromium on SwiftShader at a desktop size (1280x800).
 * "cold": a fresh browser each run (no shader cache); "warm": a second page
 * in the same browser. Also `renderer-ready` (the programs compiled).
 *
 *   npx tsx bench/first-pixel.ts [--runs 3]     (after npm run build:web)
 * `npm run bench` prints it too (runFirstPixel).
 */
import type { Browser } from 'playwright-core';
import { launchChromium } from '../src/node/session';
import { serveDirectory } from '../src/node/server';
import { projectRoot } from './common';

export interface FirstPixelResult {
  runs: number;
  viewport: { width: number; height: number };
  coldMs: number[];
  warmMs: number[];
  /** navigation -> renderer constructed (programs compiled), cold runs. */
  rendererReadyMs: number[];
  medianColdMs: number;
  medianWarmMs: number;
}

const VIEWPORT = { width: 1280, height: 800 };

async function measure(browser: Browser, url: string): Promise<{ firstPixel: number; ready: number }> {
  const page = await browser.newPage({ viewport: VIEWPORT, deviceScaleFactor: 1 });
  try {
    await page.goto(url);
    await page.waitForFunction(() => document.body.dataset.firstPixelMs !== undefined, undefined, { timeout: 60_000 });
    return await page.evaluate(() => ({
      firstPixel: Number(document.body.dataset.firstPixelMs),
      ready: performance.getEntriesByName('renderer-ready')[0]?.startTime ?? NaN,
    }));
  } finally {
    await page.close();
  }
}

const median = (values: number[]) => [...values].sort((a, b) => a - b)[Math.floor(values.length / 2)] ?? NaN;

export async function runFirstPixel(runs = 3, log: (line: string) => void = () => {}): Promise<FirstPixelResult> {
  const server = await serveDirectory(new URL('dist/web/', projectRoot()).pathname);
  const coldMs: number[] = [];
  const warmMs: number[] = [];
  const rendererReadyMs: number[] = [];
  try {
    for (let run = 0; run < runs; run++) {
      const browser = await launchChromium();
      try {
        const cold = await measure(browser, server.url);
        const warm = await measure(browser, server.url);
        coldMs.push(cold.firstPixel);
        rendererReadyMs.push(cold.ready);
        warmMs.push(warm.firstPixel);
        log(`first pixel run ${run + 1}: cold ${cold.firstPixel.toFixed(0)} ms (renderer ready ${cold.ready.toFixed(0)} ms), warm ${warm.firstPixel.toFixed(0)} ms`);
      } finally {
        await browser.close();
      }
    }
  } finally {
    await server.close();
  }
  return { runs, viewport: VIEWPORT, coldMs, warmMs, rendererReadyMs, medianColdMs: median(coldMs), medianWarmMs: median(warmMs) };
}

export function formatFirstPixel(r: FirstPixelResult): string {
  return `time to first pixel (page, ${r.viewport.width}x${r.viewport.height}, median of ${r.runs}): cold ${r.medianColdMs.toFixed(0)} ms, warm ${r.medianWarmMs.toFixed(0)} ms (renderer ready ${median(r.rendererReadyMs).toFixed(0)} ms)`;
}

// Run directly (not when bundled into dist/cli/bench.js, whose import.meta.url is the bundle's).
if (/first-pixel\.[cm]?[jt]s$/.test(process.argv[1] ?? '')) {
  const at = process.argv.indexOf('--runs');
  const runs = at > 0 ? Number(process.argv[at + 1]) : 3;
  runFirstPixel(runs, (line) => console.error(line))
    .then((result) => console.log(formatFirstPixel(result)))
    .catch((error) => {
      console.error(error instanceof Error ? error.message : error);
      process.exit(1);
    });
}
