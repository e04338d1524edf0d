/**
 * Cost of the denoiser's guide buffers (PathTracerOptions.aovs): the same
 * frames (render(1) each, as the page draws them) with and without the AOV
 * pass, interleaved in rounds, timed by wall clock and by the CPU time of the
 * GPU process (where SwiftShader runs; other load disturbs it less).
 *   npx tsx bench/aov-cost.ts [--scene seed|FILE.json] [--size 512x384] [--frames 16] [--rounds 3]
 * With aovs on, each of the first AOV_SAMPLES frames also adds one guide
 * sample; the difference per frame is the pass's cost at 1 spp. Then the
 * same for one draw of AOV_SAMPLES samples (what readAovs() costs when the
 * guides were not kept: one draw pays the pass's fixed cost once).
 */
import { readFileSync } from 'node:fs';
import { openRenderSession, type RenderSession } from '../src/node/session';
import { parseSceneText } from '../src/scene/schema';
import type { Scene } from '../src/scene/types';
import { gpuProcessCpuSeconds, projectRoot } from './common';

/** AOV_SAMPLES of src/render/PathTracer.ts (which Node cannot import: it bundles shader text through Vite). */
const AOV_SAMPLES = 16;

function arg(name: string, fallback: string): string {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 ? process.argv[i + 1] : fallback;
}

const sceneName = arg('scene', 'seed');
const [width, height] = arg('size', '512x384').split('x').map(Number);
const frames = Number(arg('frames', '16'));
const rounds = Number(arg('rounds', '3'));
const scenePath = sceneName.endsWith('.json') ? sceneName : new URL(`test/fixtures/scenes/${sceneName}.json`, projectRoot());
const scene: Scene = parseSceneText(readFileSync(scenePath, 'utf8'));

interface Cost { wallMs: number; cpuMs: number }

/** Milliseconds per frame of `frames` frames of one sample each, after a warm-up (compiles). */
async function frameCost(session: RenderSession, aovs: boolean): Promise<Cost> {
  await session.load(scene, { width, height, seed: 1, aovs });
  await session.render(1);
  await session.reset();
  const cpuStart = gpuProcessCpuSeconds() ?? NaN;
  const start = performance.now();
  for (let f = 0; f < frames; f++) await session.render(1);
  const wallMs = performance.now() - start;
  const cpuMs = ((gpuProcessCpuSeconds() ?? NaN) - cpuStart) * 1000;
  return { wallMs: wallMs / frames, cpuMs: cpuMs / frames };
}

/** Milliseconds of one draw of AOV_SAMPLES colour samples (with as many guide samples when `aovs`). */
async function drawCost(session: RenderSession, aovs: boolean): Promise<Cost> {
  await session.load(scene, { width, height, seed: 1, aovs });
  await session.render(1);
  await session.reset();
  const cpuStart = gpuProcessCpuSeconds() ?? NaN;
  const start = performance.now();
  await session.page.evaluate((n) => window.pathtrace.render(n, n), AOV_SAMPLES);
  return { wallMs: performance.now() - start, cpuMs: ((gpuProcessCpuSeconds() ?? NaN) - cpuStart) * 1000 };
}

function summary(what: string, off: Cost[], on: Cost[]): string {
  const median = (v: number[]) => [...v].sort((x, y) => x - y)[Math.floor(v.length / 2)];
  const extra = (key: keyof Cost) => median(on.map((b, i) => b[key] - off[i][key]));
  const ratio = (key: keyof Cost) => median(on.map((b, i) => b[key] / off[i][key]));
  return `${sceneName} ${width}x${height}, ${what}: the guide pass adds ${extra('wallMs').toFixed(1)} ms ` +
    `(${extra('cpuMs').toFixed(1)} ms CPU; x${ratio('cpuMs').toFixed(2)} of the colour alone), medians of ${rounds} rounds`;
}

const session = await openRenderSession();
try {
  const runs = { frameOff: [] as Cost[], frameOn: [] as Cost[], drawOff: [] as Cost[], drawOn: [] as Cost[] };
  const show = (c: Cost) => `${c.wallMs.toFixed(1)} ms (${c.cpuMs.toFixed(1)} CPU)`;
  for (let round = 0; round < rounds; round++) {
    runs.frameOff.push(await frameCost(session, false));
    runs.frameOn.push(await frameCost(session, true));
    runs.drawOff.push(await drawCost(session, false));
    runs.drawOn.push(await drawCost(session, true));
    console.log(
      `round ${round + 1}: 1-spp frame ${show(runs.frameOff[round])}, with guides ${show(runs.frameOn[round])}; ` +
        `${AOV_SAMPLES}-spp draw ${show(runs.drawOff[round])}, with guides ${show(runs.drawOn[round])}`,
    );
  }
  console.log(summary('per 1-spp frame', runs.frameOff, runs.frameOn));
  console.log(summary(`one draw of ${AOV_SAMPLES} spp`, runs.drawOff, runs.drawOn));
} finally {
  await session.close();
}
