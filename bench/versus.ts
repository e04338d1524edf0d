/**
 * Path rate of two builds of the page, interleaved in one run (so machine
 * load hits both alike): e.g. the first working version against the current
 * one on the seed scene at 512x384, the throughput target.
 *   npx tsx bench/versus.ts OTHER_WEB_ROOT [--scene seed|FILE.json] [--size 512x384] [--seconds 6] [--rounds 4]
 * OTHER_WEB_ROOT is another checkout's dist/web (its headless page must have
 * the same load/render API). Prints paths/s per round and the median ratio.
 */
import { readFileSync } from 'node:fs';
import { openRenderSession, webRoot } from '../src/node/session';
import { parseSceneText } from '../src/scene/schema';
import { projectRoot } from './common';

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
const scenePath = sceneName.endsWith('.json') ? sceneName : new URL(`test/fixtures/scenes/${sceneName}.json`, projectRoot());
const scene = parseSceneText(readFileSync(scenePath, 'utf8'));

async function pathRate(root: string): Promise<number> {
  const session = await openRenderSession({ webRoot: root });
  try {
    await session.load(scene, { width, height, seed: 1 });
    await session.render(1); // compile and warm up outside the clock
    const start = performance.now();
    let spp = 1;
    while (performance.now() - start < seconds * 1000) spp = await session.render(2);
    return ((spp - 1) * width * height) / ((performance.now() - start) / 1000);
  } finally {
    await session.close();
  }
}

const rates: { other: number[]; current: number[] } = { other: [], current: [] };
for (let round = 0; round < rounds; round++) {
  rates.other.push(await pathRate(other));
  rates.current.push(await pathRate(webRoot()));
  console.log(`round ${round + 1}: other ${(rates.other[round] / 1e6).toFixed(3)} M paths/s, current ${(rates.current[round] / 1e6).toFixed(3)} M paths/s`);
}
const median = (v: number[]) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];
const ratios = rates.current.map((c, i) => c / rates.other[i]);
console.log(`${sceneName} ${width}x${height}: current / other = ${median(ratios).toFixed(2)} (median of ${rounds} interleaved rounds)`);
