/**
 * Shader compile time of two builds: each load() in a fresh browser session
 * creates a PathTracer, which compiles the trace programs compiled up front
 * (and the scene's own variant); alternating builds cancel the machine's
 * load swings. Prints the median of `--rounds` rounds per build.
 *   npx tsx scripts/compile-time.ts OTHER_WEB_ROOT [--scene test/fixtures/scenes/seed.json] [--rounds 3]
 */
import { readFileSync } from 'node:fs';
import { openRenderSession } from '../src/node/session';
import { parseSceneText } from '../src/scene/schema';
import { readSceneFiles } from '../src/node/sceneFiles';

function option(argv: string[], name: string, fallback: string): string {
  const i = argv.indexOf(`--${name}`);
  return i >= 0 ? argv[i + 1] : fallback;
}

async function loadSeconds(webRoot: string | undefined, sceneFile: string): Promise<number> {
  const scene = parseSceneText(readFileSync(sceneFile, 'utf8'));
  const { files } = await readSceneFiles(scene, sceneFile); // environment maps, meshes
  const session = await openRenderSession(webRoot ? { webRoot } : {});
  try {
    const start = performance.now();
    await session.load(scene, { width: 64, height: 48, seed: 1 }, files);
    await session.render(1);
    return (performance.now() - start) / 1000;
  } finally {
    await session.close();
  }
}

async function main(argv: string[]): Promise<void> {
  const other = argv[0];
  const sceneFile = option(argv, 'scene', 'test/fixtures/scenes/seed.json');
  const rounds = Number(option(argv, 'rounds', '3'));
  const times: { current: number[]; other: number[] } = { current: [], other: [] };
  for (let r = 0; r < rounds; r++) {
    times.other.push(await loadSeconds(other, sceneFile));
    times.current.push(await loadSeconds(undefined, sceneFile));
    console.log(`round ${r + 1}: other ${times.other[r].toFixed(2)} s, current ${times.current[r].toFixed(2)} s`);
  }
  const median = (xs: number[]) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
  console.log(`load + compile + 1 spp at 64x48 (${sceneFile}): current ${median(times.current).toFixed(2)} s, other ${median(times.other).toFixed(2)} s, ratio ${(median(times.current) / median(times.other)).toFixed(2)}`);
}

main(process.argv.slice(2)).catch((error) => {
  console.error(error);
  process.exit(1);
});
