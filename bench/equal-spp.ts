/**
 * Error at equal samples of two builds of the page: relMSE against the
 * scene's Mitsuba reference after `--spp` samples, for `--seeds` seeds each
 * (mean, median and worst: heavy-tailed estimators differ most in the mean
 * and the worst seed). Independent of the machine's load, unlike the
 * equal-time rows of `npm run bench`; multiply by the path-rate ratio of
 * bench/versus.ts for the equal-time ratio.
 *   npx tsx bench/equal-spp.ts OTHER_WEB_ROOT [--scene lights] [--spp 128] [--seeds 6]
 */
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { openRenderSession, webRoot } from '../src/node/session';
import { parseSceneText } from '../src/scene/schema';
import { readSceneFiles } from '../src/node/sceneFiles';
import { relativeMse } from '../src/node/imageMetrics';
import { decodePfm } from '../src/image/pfm';
import { projectRoot } from './common';

function arg(name: string, fallback: string): string {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 ? process.argv[i + 1] : fallback;
}

const other = process.argv[2];
if (!other || other.startsWith('--')) {
  console.error('usage: npx tsx bench/equal-spp.ts OTHER_WEB_ROOT [--scene lights] [--spp 128] [--seeds 6]');
  process.exit(2);
}
const name = arg('scene', 'lights');
const spp = Number(arg('spp', '128'));
const seeds = Number(arg('seeds', '6'));
const scenePath = fileURLToPath(new URL(`test/fixtures/scenes/${name}.json`, projectRoot()));
const scene = parseSceneText(readFileSync(scenePath, 'utf8'));
const { files } = await readSceneFiles(scene, scenePath);
const pfm = decodePfm(readFileSync(new URL(`test/fixtures/references/${name}.pfm`, projectRoot())));
const reference = { width: pfm.width, height: pfm.height, channels: 3, data: pfm.rgb };

async function errors(root: string): Promise<number[]> {
  const session = await openRenderSession({ webRoot: root });
  try {
    const out: number[] = [];
    for (let seed = 1; seed <= seeds; seed++) {
      await session.load(scene, { width: scene.image.width, height: scene.image.height, seed }, files);
      await session.render(spp);
      out.push(relativeMse({ width: scene.image.width, height: scene.image.height, channels: 4, data: await session.readLinear() }, reference));
    }
    return out;
  } finally {
    await session.close();
  }
}

const summary = (e: number[]) => {
  const sorted = [...e].sort((a, b) => a - b);
  return { mean: e.reduce((a, b) => a + b, 0) / e.length, median: sorted[Math.floor(e.length / 2)], worst: sorted[sorted.length - 1] };
};
const [current, previous] = [summary(await errors(webRoot())), summary(await errors(other))];
const f = (x: number) => x.toExponential(2);
console.log(`${name} at ${spp} spp, ${seeds} seeds: relMSE mean / median / worst`);
console.log(`  current ${f(current.mean)} / ${f(current.median)} / ${f(current.worst)}`);
console.log(`  other   ${f(previous.mean)} / ${f(previous.median)} / ${f(previous.worst)}`);
console.log(`  current / other: mean ${(current.mean / previous.mean).toFixed(2)}, median ${(current.median / previous.median).toFixed(2)}, worst ${(current.worst / previous.worst).toFixed(2)}`);
