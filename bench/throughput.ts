/**
 * Path rate of one scene at one resolution (default: the seed scene at
 * 512x384, its 6 bounces), recorded as bench/results/PREFIX-*.json.
 *   npx tsx bench/throughput.ts [--scene seed] [--size 512x384] [--seconds 10] [--repeat 3] [--prefix throughput] [--note TEXT]
 */
import { readFileSync } from 'node:fs';
import { openRenderSession } from '../src/node/session';
import { parseSceneText } from '../src/scene/schema';
import { gitRevision, machineInfo, measureThroughput, projectRoot, writeResult } from './common';

function option(argv: string[], name: string, fallback: string): string {
  const i = argv.indexOf(`--${name}`);
  return i >= 0 && i + 1 < argv.length ? argv[i + 1] : fallback;
}

async function main(argv: string[]): Promise<void> {
  const name = option(argv, 'scene', 'seed');
  const [width, height] = option(argv, 'size', '512x384').split('x').map(Number);
  const seconds = Number(option(argv, 'seconds', '10'));
  const repeat = Number(option(argv, 'repeat', '3'));
  const scene = parseSceneText(readFileSync(new URL(`test/fixtures/scenes/${name}.json`, projectRoot()), 'utf8'));
  const session = await openRenderSession();
  try {
    const { renderer } = await session.load(scene, { width, height, seed: 1 });
    const runs = [];
    for (let r = 0; r < repeat; r++) {
      const t = await measureThroughput(session, scene, { width, height }, seconds, r + 1);
      console.log(`${name} ${width}x${height} ${t.maxBounces} bounces: ${t.megaPathsPerSecond.toFixed(3)} M paths/s, ${t.megaPathsPerCpuSecond?.toFixed(3)} M paths/CPU-s (${t.spp} spp in ${t.seconds.toFixed(2)} s, startup ${t.startupSeconds.toFixed(2)} s)`);
      runs.push(t);
    }
    const best = Math.max(...runs.map((t) => t.megaPathsPerSecond));
    const cpu = runs.map((t) => t.megaPathsPerCpuSecond ?? NaN).sort((a, b) => a - b)[Math.floor(runs.length / 2)];
    const prefix = option(argv, 'prefix', 'throughput');
    const file = prefix === 'none' ? '(not saved)' : writeResult(prefix, {
      kind: 'throughput',
      date: new Date().toISOString(),
      revision: gitRevision(),
      note: option(argv, 'note', ''),
      scene: name,
      machine: await machineInfo(session),
      renderer,
      bestMegaPathsPerSecond: best,
      medianMegaPathsPerCpuSecond: cpu,
      runs,
    });
    console.log(`best ${best.toFixed(3)} M paths/s, median ${cpu.toFixed(3)} M paths/CPU-s -> ${file}`);
  } finally {
    await session.close();
  }
}

main(process.argv.slice(2)).catch((error) => {
  console.error(error);
  process.exit(1);
});
