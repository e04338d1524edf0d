/**
 * A/B of sampler variants, interleaved to cancel the machine's load swings:
 * path rate (median of alternating short runs) and relMSE at fixed spp
 * (mean over seeds), per scene.
 *   npx tsx bench/ab.ts [--scenes seed,glossy] [--samplers independent,kronecker] [--spp 16] [--seeds 3] [--rounds 4] [--seconds 1.5] [--size WxH]
 */
import { readFileSync } from 'node:fs';
import { relativeMse, type LinearImage } from '../src/node/imageMetrics';
import { openRenderSession, type LoadOptions } from '../src/node/session';
import type { SamplerKind } from '../src/render/sampling';
import { parseSceneText } from '../src/scene/schema';
import { decodePfm } from '../src/image/pfm';
import { projectRoot, renderFor } from './common';
import { downsample } from './run';

function option(argv: string[], name: string, fallback: string): string {
  const i = argv.indexOf(`--${name}`);
  return i >= 0 && i + 1 < argv.length ? argv[i + 1] : fallback;
}

const median = (v: number[]) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];

async function main(argv: string[]): Promise<void> {
  const scenes = option(argv, 'scenes', 'seed,glossy,small-light,mirrors').split(',');
  const samplers = option(argv, 'samplers', 'independent,kronecker').split(',') as SamplerKind[];
  const spp = Number(option(argv, 'spp', '16'));
  const seeds = Number(option(argv, 'seeds', '3'));
  const rounds = Number(option(argv, 'rounds', '4'));
  const seconds = Number(option(argv, 'seconds', '1.5'));
  const root = projectRoot();
  const session = await openRenderSession();
  try {
    for (const name of scenes) {
      const scene = parseSceneText(readFileSync(new URL(`test/fixtures/scenes/${name}.json`, root), 'utf8'));
      const pfm = decodePfm(readFileSync(new URL(`test/fixtures/references/${name}.pfm`, root)));
      const reference: LinearImage = { width: pfm.width, height: pfm.height, channels: 3, data: pfm.rgb };
      const [w, h] = option(argv, 'size', `${pfm.width}x${pfm.height}`).split('x').map(Number);
      const rates = new Map<SamplerKind, number[]>(samplers.map((s) => [s, []]));
      const cpuRates = new Map<SamplerKind, number[]>(samplers.map((s) => [s, []]));
      const errors = new Map<SamplerKind, number[]>(samplers.map((s) => [s, []]));
      for (let r = 0; r < rounds; r++) {
        for (const sampler of r % 2 ? [...samplers].reverse() : samplers) {
          const load = (seed: number) => session.load(scene, { width: w, height: h, seed, sampler } as LoadOptions);
          await load(1);
          const m = await measureThroughputLoaded(session, w * h, seconds);
          rates.get(sampler)!.push(m.wall);
          cpuRates.get(sampler)!.push(m.cpu);
        }
      }
      for (let seed = 1; seed <= seeds; seed++) {
        for (const sampler of samplers) {
          await session.load(scene, { width: pfm.width, height: pfm.height, seed: 100 + seed, sampler } as LoadOptions);
          await session.render(spp);
          const image = { width: pfm.width, height: pfm.height, channels: 4, data: await session.readLinear() };
          errors.get(sampler)!.push(relativeMse(downsample(image, 1), reference));
        }
      }
      const base = samplers[0];
      // Efficiency = 1 / (relMSE x cost per path), cost from GPU-process CPU time.
      const eff = (s: SamplerKind) => median(cpuRates.get(s)!) / mean(errors.get(s)!);
      for (const s of samplers) {
        console.log(
          `${name} ${w}x${h} ${s.padEnd(11)} ${median(rates.get(s)!).toFixed(3)} Mpath/s wall, ${median(cpuRates.get(s)!).toFixed(3)} Mpath/CPU-s (runs ${cpuRates.get(s)!.map((x) => x.toFixed(2)).join(' ')}) ` +
            `relMSE@${spp}spp ${mean(errors.get(s)!).toExponential(3)}  efficiency vs ${base}: ${(eff(s) / eff(base)).toFixed(2)}x`,
        );
      }
    }
  } finally {
    await session.close();
  }
}

const mean = (v: number[]) => v.reduce((a, b) => a + b, 0) / v.length;

/** Path rate of the loaded scene (first draw = JIT, not timed). */
async function measureThroughputLoaded(
  session: Awaited<ReturnType<typeof openRenderSession>>,
  pixels: number,
  seconds: number,
): Promise<{ wall: number; cpu: number }> {
  await session.render(1);
  const run = await renderFor(session, seconds, 0.25);
  return { wall: (run.spp * pixels) / run.seconds / 1e6, cpu: (run.spp * pixels) / (run.cpuSeconds ?? NaN) / 1e6 };
}

main(process.argv.slice(2)).catch((error) => {
  console.error(error);
  process.exit(1);
});
