/**
 * What tiling costs: the same samples rendered in draws of various sizes in
 * the headless renderer, interleaved in rounds so the machine's load swings
 * hit every size alike. Prints, per draw size, the time per sample (wall and
 * CPU of the GPU process, where SwiftShader runs) and its ratio to untiled
 * draws (one draw per sample). For the seed scene and a generated mesh:
 *   npx tsx bench/tile-cost.ts [--scene seed|mesh] [--triangles 1000000] [--size 512x384] [--paths 1000,4000,30000] [--spp 2] [--rounds 3] [--web DIR]
 * (run after `npm run build:web`; --web: another build's dist/web).
 */
import { readFileSync } from 'node:fs';
import { openRenderSession } from '../src/node/session';
import { parseSceneText } from '../src/scene/schema';
import { gpuProcessCpuSeconds, projectRoot } from './common';
import { bumpySpherePly, meshScene } from './meshGen';

const option = (argv: string[], name: string, fallback: string) => {
  const i = argv.indexOf(`--${name}`);
  return i >= 0 && i + 1 < argv.length ? argv[i + 1] : fallback;
};
const median = (v: number[]) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];

async function main(argv: string[]): Promise<void> {
  const which = option(argv, 'scene', 'seed');
  const [width, height] = option(argv, 'size', '512x384').split('x').map(Number);
  const pixels = width * height;
  const spp = Number(option(argv, 'spp', '2'));
  const rounds = Number(option(argv, 'rounds', '3'));
  // 0 = untiled: one draw per sample.
  const sizes = [0, ...option(argv, 'paths', '1000,4000,30000').split(',').map(Number)];
  const web = option(argv, 'web', '');
  const session = await openRenderSession(web ? { webRoot: web } : {});
  try {
    const load = async () => {
      if (which === 'mesh') {
        const triangles = Number(option(argv, 'triangles', '1000000'));
        await session.load(meshScene('sphere.ply', width, height), { width, height, seed: 1 }, { 'sphere.ply': bumpySpherePly(triangles) });
      } else {
        const scene = parseSceneText(readFileSync(new URL(`test/fixtures/scenes/${which}.json`, projectRoot()), 'utf8'));
        await session.load(scene, { width, height, seed: 1 });
      }
    };
    await load();
    await session.page.evaluate(() => window.pathtrace.render(1, 1, 1e12)); // compile and warm up
    const wall = new Map<number, number[]>(sizes.map((s) => [s, []]));
    const cpu = new Map<number, number[]>(sizes.map((s) => [s, []]));
    for (let round = 0; round < rounds; round++) {
      for (const size of round % 2 ? [...sizes].reverse() : sizes) {
        await session.reset();
        const cpu0 = gpuProcessCpuSeconds();
        const t0 = performance.now();
        await session.page.evaluate(([n, p]) => window.pathtrace.render(n, 1, p), [spp, size || 1e12]);
        const seconds = (performance.now() - t0) / 1000;
        const cpu1 = gpuProcessCpuSeconds();
        wall.get(size)!.push(seconds / spp);
        if (cpu0 !== undefined && cpu1 !== undefined) cpu.get(size)!.push((cpu1 - cpu0) / spp);
      }
    }
    const base = median(wall.get(0)!);
    const baseCpu = cpu.get(0)!.length ? median(cpu.get(0)!) : NaN;
    for (const size of sizes) {
      const w = median(wall.get(size)!);
      const c = cpu.get(size)!.length ? median(cpu.get(size)!) : NaN;
      const label = size ? `${size} paths per draw (${Math.ceil(pixels / size)} draws per sample)` : 'untiled (1 draw per sample)';
      console.log(`${which} ${width}x${height}, ${label}: ${(w * 1000).toFixed(0)} ms per sample (x${(w / base).toFixed(3)}), CPU ${(c * 1000).toFixed(0)} ms (x${(c / baseCpu).toFixed(3)})`);
    }
  } finally {
    await session.close();
  }
}

main(process.argv.slice(2)).catch((error) => {
  console.error(error);
  process.exit(1);
});
