/**
 * `npm run bench`: the convergence benchmark (see bench/run.ts).
 *   npm run bench -- [--scenes seed,glossy] [--times 2,5,10] [--scale 1] [--target 0.02]
 *                    [--samplers kronecker,independent,adaptive] [--no-mitsuba] [--quick] [--no-save] [--json]
 * --quick: 0.5 s per scene, no Mitsuba, no result file: only checks that the benchmark runs (CI).
 * Results go to bench/results/bench-<date>.json.
 */
import { formatTable, runBench, type BenchOptions } from './run';
import { writeResult } from './common';
import { formatFirstPixel, runFirstPixel } from './first-pixel';
import { formatEnvmapLoad, measureEnvmapLoad } from './envmap-load';
import { formatManyLights, runManyLights } from './many-lights';

function parse(argv: string[]): { options: BenchOptions; save: boolean; json: boolean } {
  const options: BenchOptions = { log: (line) => console.error(line) };
  let save = true;
  let json = false;
  const list = (v: string | undefined) => (v ?? '').split(',').filter(Boolean);
  for (let i = 0; i < argv.length; i++) {
    const arg = argv[i];
    switch (arg) {
      case '--scenes': options.scenes = list(argv[++i]); break;
      case '--times': options.times = list(argv[++i]).map(Number); break;
      case '--scale': options.scale = Number(argv[++i]); break;
      case '--target': options.target = Number(argv[++i]); break;
      case '--samplers': options.samplers = list(argv[++i]) as BenchOptions['samplers']; break;
      case '--seed': options.seed = Number(argv[++i]); break;
      case '--mitsuba': options.mitsuba = true; break;
      case '--no-mitsuba': options.mitsuba = false; break;
      case '--no-save': save = false; break;
      case '--json': json = true; break;
      case '--quick':
        options.times = [0.5];
        options.mitsuba ??= false;
        save = false;
        break;
      default:
        console.error(`unknown option ${arg}\nusage: bench [--scenes a,b] [--times 2,5,10] [--scale N] [--target 0.02] [--seed N] [--samplers kronecker,independent,adaptive] [--mitsuba|--no-mitsuba] [--quick] [--no-save] [--json]`);
        process.exit(2);
    }
  }
  const times = options.times ?? [];
  if (times.some((t) => !(t > 0)) || times.some((t, i) => i > 0 && t <= times[i - 1])) throw new Error('--times must be ascending positive seconds');
  if (options.scale !== undefined && !(Number.isInteger(options.scale) && options.scale >= 1)) throw new Error('--scale must be an integer >= 1');
  return { options, save, json };
}

const times = (options: BenchOptions) => Math.max(0, ...(options.times ?? [Infinity]));

async function main(): Promise<void> {
  const { options, save, json } = parse(process.argv.slice(2));
  const bench = await runBench(options);
  // The page's time to first pixel (load -> first rendered frame), a fresh browser per run.
  const firstPixel = await runFirstPixel(times(options) <= 0.5 ? 1 : 3, options.log);
  // Loading a 2k environment map: decode and sampling distribution (Node; the page runs the same code in a Worker).
  const loadRuns = times(options) <= 0.5 ? 1 : 5;
  const envmapLoad = measureEnvmapLoad(loadRuns);
  // Issue 21's row: 64 mixed lights against one (path rate, interleaved rounds).
  const quick = times(options) <= 0.5;
  const manyLights = await runManyLights({ rounds: quick ? 1 : 3, seconds: quick ? 0.5 : 4 }, options.log);
  const result = { ...bench, firstPixel, envmapLoad, manyLights };
  console.log(`${result.renderer} | ${result.machine.browser} | ${result.machine.cpu} x${result.machine.cores} | rev ${result.revision}${result.mitsubaVersion ? ` | Mitsuba ${result.mitsubaVersion} scalar_rgb` : ''}`);
  console.log(formatTable(result));
  console.log(formatFirstPixel(firstPixel));
  console.log(formatEnvmapLoad(envmapLoad, loadRuns));
  console.log(formatManyLights(manyLights));
  if (json) console.log(JSON.stringify(result));
  if (save) console.log(`saved ${writeResult('bench', result)}`);
}

main().catch((error) => {
  console.error(error instanceof Error ? error.message : error);
  process.exit(1);
});
