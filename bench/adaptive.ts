/**
 * Adaptive sampling against uniform sampling (PathTracerOptions.adaptive),
 * at equal time and at equal paths, interleaved in one session so machine
 * load hits both alike: relMSE against the scene's Mitsuba reference after
 * `--seconds` of rendering (chunks of about 0.5 s, as the CLI's --time), per
 * seed, and the paths each drew.
 *   npx tsx bench/adaptive.ts [--scenes bunny,instanced] [--seconds 6] [--seeds 3]
 */
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { openRenderSession } from '../src/node/session';
import { parseSceneText } from '../src/scene/schema';
import { readSceneFiles } from '../src/node/sceneFiles';
import { relativeMse } from '../src/node/imageMetrics';
import { decodePfm } from '../src/image/pfm';
import { projectRoot, writeResult } from './common';

function arg(name: string, fallback: string): string {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 ? process.argv[i + 1] : fallback;
}

const scenes = arg('scenes', 'bunny,instanced').split(',');
const seconds = Number(arg('seconds', '6'));
const seeds = Number(arg('seeds', '3'));
const session = await openRenderSession();
const results: Record<string, { adaptive: boolean; seed: number; spp: number; relMse: number }[]> = {};
try {
  for (const name of scenes) {
    const scenePath = fileURLToPath(new URL(`test/fixtures/scenes/${name}.json`, projectRoot()));
    const scene = parseSceneText(readFileSync(scenePath, 'utf8'));
    const { files } = await readSceneFiles(scene, scenePath);
    const pfm = decodePfm(readFileSync(new URL(`test/fixtures/references/${name}.pfm`, projectRoot())));
    const reference = { width: pfm.width, height: pfm.height, channels: 3, data: pfm.rgb };
    const size = { width: scene.image.width, height: scene.image.height };
    results[name] = [];
    for (let seed = 1; seed <= seeds; seed++) {
      for (const adaptive of [false, true]) {
        await session.load(scene, { ...size, seed, adaptive }, files);
        await session.render(1);
        await session.reset();
        const start = performance.now();
        let spp = 0;
        let rate = 0;
        while ((performance.now() - start) / 1000 < seconds) {
          const left = seconds - (performance.now() - start) / 1000;
          const chunk = rate === 0 ? 1 : Math.max(1, Math.round(rate * Math.min(0.5, left)));
          spp = await session.render(chunk);
          rate = spp / ((performance.now() - start) / 1000);
        }
        const relMse = relativeMse({ ...size, channels: 4, data: await session.readLinear() }, reference);
        results[name].push({ adaptive, seed, spp, relMse });
        console.log(`${name} seed ${seed} ${adaptive ? 'adaptive' : 'uniform '}: ${spp} spp, relMSE ${relMse.toExponential(3)}`);
      }
    }
    const mean = (adaptive: boolean, key: 'spp' | 'relMse') => {
      const rows = results[name].filter((r) => r.adaptive === adaptive);
      return rows.reduce((s, r) => s + r[key], 0) / rows.length;
    };
    const time = mean(true, 'relMse') / mean(false, 'relMse');
    const paths = time * (mean(true, 'spp') / mean(false, 'spp'));
    console.log(`${name}: adaptive / uniform relMSE at equal time ${time.toFixed(2)}, at equal paths ${paths.toFixed(2)}; paths ${(mean(true, 'spp') / mean(false, 'spp')).toFixed(2)}x (means of ${seeds} seeds, ${seconds} s each)`);
  }
} finally {
  await session.close();
}
writeResult('adaptive', { seconds, seeds, results });
