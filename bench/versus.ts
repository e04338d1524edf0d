/**
 * Path rate of two builds of the page, interleaved in one run (so machine
 * load hits both alike): e.g. the first working version against the current
 * one on the seed scene at 512x384, the throughput target.
 *   npx tsx bench/versus.ts OTHER_WEB_ROOT [--scene seed|FILE.json] [--size 512x384] [--seconds 6] [--rounds 4]
 * OTHER_WEB_ROOT is another checkout's dist/web (its headless page must have
 * the same load/render API). Prints paths per wall second and per CPU second
 * of the GPU process (where SwiftShader runs; other load on the shared
 * machine disturbs it less) per round, and the median ratios.
 */
import { readFileSync } from 'node:fs';
import { openRenderSession, webRoot } from '../src/node/session';
import { parseSceneText } from '../src/scene/schema';
import { readSceneFiles } from '../src/node/sceneFiles';
import { fileURLToPath } from 'node:url';
import { gitRevision, projectRoot, renderFor, writeResult } from './common';

function arg(name: string, fallback: string): string {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 ? process.argv[i + 1] : fallback;
}

const other = process.argv[2];
if (!other || other.startsWith('--')) {
  console.error('usage: npx tsx bench/versus.ts OTHER_WEB_ROOT [--scene seed] [--size 512x384] [--seconds 6] [--rounds 4]');
  process.exit(2);
}
const sceneName = arg('scene', 'seed');
const [width, height] = arg('size', '512x384').split('x').map(Number);
const seconds = Number(arg('seconds', '6'));
const rounds = Number(arg('rounds', '4'));
const scenePath = sceneName.endsWith('.json') ? sceneName : fileURLToPath(new URL(`test/fixtures/scenes/${sceneName}.json`, projectRoot()));
const scene = parseSceneText(readFileSync(scenePath, 'utf8'));
const { files } = await readSceneFiles(scene, scenePath); // environment maps, meshes

interface Rate { wall: number; cpu: number }

async function pathRate(root: string): Promise<Rate> {
  const session = await openRenderSession({ webRoot: root });
  try {
    await session.load(scene, { width, height, seed: 1 }, files);
    await session.render(1); // compile and warm up outside the clock
    const run = await renderFor(session, seconds, 0.5);
    const paths = run.spp * width * height;
    return { wall: paths / run.seconds, cpu: paths / (run.cpuSeconds ?? NaN) };
  } finally {
    await session.close();
  }
}

const rates: { other: Rate[]; current: Rate[] } = { other: [], current: [] };
const mega = (r: number) => (r / 1e6).toFixed(3);
for (let round = 0; round < rounds; round++) {
  rates.other.push(await pathRate(other));
  rates.current.push(await pathRate(webRoot()));
  const [o, c] = [rates.other[round], rates.current[round]];
  console.log(`round ${round + 1}: other ${mega(o.wall)} M paths/s (${mega(o.cpu)} per CPU-s), current ${mega(c.wall)} M paths/s (${mega(c.cpu)} per CPU-s)`);
}
const median = (v: number[]) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];
const ratio = (key: keyof Rate) => median(rates.current.map((c, i) => c[key] / rates.other[i][key])).toFixed(2);
console.log(`${sceneName} ${width}x${height}: current / other = ${ratio('wall')} per wall second, ${ratio('cpu')} per CPU second (medians of ${rounds} interleaved rounds)`);
const file = writeResult('versus', {
  date: new Date().toISOString(),
  scene: sceneName,
  width,
  height,
  maxBounces: scene.render.maxBounces,
  secondsPerRun: seconds,
  current: { revision: gitRevision(), rates: rates.current },
  other: { webRoot: other, rates: rates.other },
  ratio: { wall: Number(ratio('wall')), cpu: Number(ratio('cpu')) },
});
console.log(`saved ${file}`);
