/**
 * Renders scenes with two builds of the page at the same seed and reports
 * whether the linear images are bit-identical (and the largest difference).
 *   npx tsx scripts/compare-builds.ts OTHER_WEB_ROOT [--spp 8] [scene.json ...]
 * Used to check that a restructuring changes nothing (the files a scene names are read as the CLI reads them).
 */
import { readFileSync } from 'node:fs';
import { openRenderSession } from '../src/node/session';
import { parseSceneText } from '../src/scene/schema';
import { readSceneFiles } from '../src/node/sceneFiles';

async function main(argv: string[]): Promise<void> {
  const other = argv[0];
  const sppIndex = argv.indexOf('--spp');
  const spp = sppIndex >= 0 ? Number(argv[sppIndex + 1]) : 8;
  const files = argv.slice(1).filter((a, i, all) => a !== '--spp' && all[i - 1] !== '--spp');
  const ours = await openRenderSession();
  const theirs = await openRenderSession({ webRoot: other });
  try {
    for (const file of files) {
      const scene = parseSceneText(readFileSync(file, 'utf8'));
      const { files: assets } = await readSceneFiles(scene, file); // environment maps, meshes, textures
      const images = [];
      for (const session of [ours, theirs]) {
        await session.load(scene, { width: scene.image.width, height: scene.image.height, seed: 7 }, assets);
        await session.render(spp);
        images.push(await session.readLinear());
      }
      const [a, b] = images;
      let differing = 0;
      let worst = 0;
      for (let i = 0; i < a.length; i++) {
        if (a[i] !== b[i] && !(Number.isNaN(a[i]) && Number.isNaN(b[i]))) {
          differing++;
          worst = Math.max(worst, Math.abs(a[i] - b[i]) / Math.max(1e-6, Math.abs(b[i])));
        }
      }
      console.log(`${file}: ${differing === 0 ? 'bit-identical' : `${differing} of ${a.length} floats differ, worst relative ${worst.toExponential(2)}`}`);
    }
  } finally {
    await ours.close();
    await theirs.close();
  }
}

main(process.argv.slice(2)).catch((error) => {
  console.error(error);
  process.exit(1);
});
