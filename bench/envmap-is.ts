/**
 * Importance sampling of the environment map, measured: relMSE against the
 * Mitsuba reference at equal times for the `envmap` scene (or another scene
 * with a map) rendered three ways, interleaved in one Chromium:
 *   importance  the renderer as shipped: the map is an emitter of the light
 *               interface, sampled from its luminance distribution, MIS
 *   uniform     the map still in the light interface, but sampled uniformly
 *               over the sphere (MIS with the BSDF as before)
 *   bsdfOnly    the light interface never picks the map (its light samples
 *               have pdf 0 and lightPdf is 0 at escaped rays): the map is
 *               found only by BSDF sampling, weighted 1
 * The two baselines are bench-only text patches of the compiled trace shader
 * (applied in the page at shaderSource() time, as bench/shader-ab.ts does);
 * the shipped shaders are unchanged. A patch that no longer matches the
 * shader's text stops the bench rather than measuring the unpatched shader.
 *
 *   npx tsx bench/envmap-is.ts [--scene envmap] [--times 2,5,10] [--seed 1] [--rounds 2] [--variants importance,uniform,bsdfOnly]
 * Rounds alternate the variants' order and the seed; the table gives means.
 * (dist/web must be built: npx vite build)
 */
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { relativeMse, type LinearImage } from '../src/node/imageMetrics';
import { openRenderSession } from '../src/node/session';
import { readSceneFiles } from '../src/node/sceneFiles';
import { decodePfm } from '../src/image/pfm';
import { parseSceneText } from '../src/scene/schema';
import { gitRevision, projectRoot, writeResult } from './common';
import { benchOurs, FIXTURES } from './run';

type Patch = [string, string];

const UNIFORM_DIRECTION =
  '{ float cz = 1.0 - 2.0 * u.y; float sr = sqrt(max(0.0, 1.0 - cz * cz)); float ph = 2.0 * PI * u.x;' +
  ' s.direction = vec3(sr * cos(ph), cz, sr * sin(ph)); pdf = 0.25 / PI; }';

/** Text edits of lights.glsl (as assembled into the trace shader) per variant. */
export const ENVIRONMENT_PATCHES: Record<string, Patch[]> = {
  importance: [],
  uniform: [
    ['s.direction = sampleEnvironment(u.xy, pdf);', UNIFORM_DIRECTION],
    ['environmentEmitterPdf() * environmentPdf(direction)', 'environmentEmitterPdf() * (0.25 / PI)'],
  ],
  bsdfOnly: [
    ['s.pdf = count > 0 ? e.pdf * pdf : 0.0;', 's.pdf = count > 0 && e.kind != EMITTER_ENVIRONMENT ? e.pdf * pdf : 0.0;'],
    ['environmentEmitterPdf() * environmentPdf(direction)', '0.0'],
  ],
};

function option(argv: string[], name: string, fallback: string): string {
  const i = argv.indexOf(`--${name}`);
  return i >= 0 && i + 1 < argv.length ? argv[i + 1] : fallback;
}

async function main(argv: string[]): Promise<void> {
  const sceneName = option(argv, 'scene', 'envmap');
  const times = option(argv, 'times', '2,5,10').split(',').map(Number);
  const seed = Number(option(argv, 'seed', '1'));
  const rounds = Number(option(argv, 'rounds', '2'));
  const variants = option(argv, 'variants', 'importance,uniform,bsdfOnly').split(',');
  for (const v of variants) if (!(v in ENVIRONMENT_PATCHES)) throw new Error(`unknown variant ${v}`);

  const sceneFile = fileURLToPath(new URL(`scenes/${sceneName}.json`, FIXTURES));
  const scene = parseSceneText(readFileSync(sceneFile, 'utf8'));
  const { files } = await readSceneFiles(scene, sceneFile);
  const pfm = decodePfm(readFileSync(new URL(`references/${sceneName}.pfm`, FIXTURES)));
  const reference: LinearImage = { width: pfm.width, height: pfm.height, channels: 3, data: pfm.rgb };
  const size = { width: pfm.width, height: pfm.height };
  const score = (image: LinearImage) => relativeMse(image, reference);

  const session = await openRenderSession();
  const page = session.page;
  await page.addInitScript(() => {
    const original = WebGL2RenderingContext.prototype.shaderSource;
    const w = window as unknown as { __patches?: [string, string][]; __patchMisses?: string[] };
    WebGL2RenderingContext.prototype.shaderSource = function (shader: WebGLShader, text: string) {
      if (text.includes('uSamplesPerDraw') && text.includes('outSum') && text.includes('#define HAS_ENV_MAP 1')) {
        for (const [search, replacement] of w.__patches ?? []) {
          if (!text.includes(search)) (w.__patchMisses ??= []).push(search);
          text = text.replace(search, replacement);
        }
      }
      return original.call(this, shader, text);
    };
  });
  await page.reload();
  await page.waitForFunction(() => document.body.dataset.ready === 'true');

  // Rounds alternate the order of the variants (and the seed): the shared
  // machine's load drifts, and equal wall time is only fair when interleaved.
  type Row = { variant: string; checkpoints: { seconds: number; spp: number; relMse: number }[]; mpaths: number };
  const runs = new Map<string, Row[]>(variants.map((v) => [v, []]));
  try {
    for (let round = 0; round < rounds; round++) {
      for (const variant of round % 2 ? [...variants].reverse() : variants) {
        await page.evaluate((p) => {
          const w = window as unknown as { __patches?: [string, string][]; __patchMisses?: string[] };
          w.__patches = p;
          w.__patchMisses = [];
        }, ENVIRONMENT_PATCHES[variant]);
        console.error(`${sceneName}: ${variant}, round ${round + 1} of ${rounds}...`);
        const { run } = await benchOurs(session, scene, size, score, times, 0.02, seed + round, 'kronecker', files);
        const misses = await page.evaluate(() => (window as unknown as { __patchMisses?: string[] }).__patchMisses ?? []);
        if (misses.length) throw new Error(`${variant}: patch text not found in the trace shader: ${misses.join(' | ')}`);
        runs.get(variant)!.push({ variant, checkpoints: run.checkpoints, mpaths: run.megaPathsPerSecond });
      }
    }
  } finally {
    await session.close();
  }
  const mean = (values: number[]) => values.reduce((a, b) => a + b, 0) / values.length;
  const rows: Row[] = variants.map((variant) => {
    const list = runs.get(variant)!;
    return {
      variant,
      mpaths: mean(list.map((r) => r.mpaths)),
      checkpoints: times.map((_, i) => ({
        seconds: mean(list.map((r) => r.checkpoints[i].seconds)),
        spp: Math.round(mean(list.map((r) => r.checkpoints[i].spp))),
        relMse: mean(list.map((r) => r.checkpoints[i].relMse)),
      })),
    };
  });
  const base = rows[0];
  console.log(`scene ${sceneName} ${size.width}x${size.height}, rev ${gitRevision()}: relMSE vs the Mitsuba reference at equal time, mean of ${rounds} interleaved rounds`);
  console.log(['variant'.padEnd(11), 'Mpath/s', ...times.map((t) => `spp@${t}s`.padStart(9)), ...times.map((t) => `relMSE@${t}s`.padStart(12)), `x ${base.variant}`].join('  '));
  for (const row of rows) {
    const ratios = row.checkpoints.map((c, i) => (c.relMse / base.checkpoints[i].relMse).toFixed(1));
    console.log([
      row.variant.padEnd(11),
      row.mpaths.toFixed(3).padStart(7),
      ...row.checkpoints.map((c) => String(c.spp).padStart(9)),
      ...row.checkpoints.map((c) => c.relMse.toExponential(2).padStart(12)),
      ratios.join(' '),
    ].join('  '));
  }
  if (!argv.includes('--no-save')) console.log(`saved ${writeResult('envmap-is', { scene: sceneName, times, seed, rounds, revision: gitRevision(), rows, runs: Object.fromEntries(runs) })}`);
}

void projectRoot;
main(process.argv.slice(2)).catch((error) => {
  console.error(error);
  process.exit(1);
});
