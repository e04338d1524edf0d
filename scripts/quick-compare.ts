/**
 * Renders fixture scenes and prints relMSE against their Mitsuba references
 * and the ratio of image means, for a quick look while developing.
 *   npx tsx scripts/quick-compare.ts [--spp 64] NAME ...   (names of test/fixtures/scenes)
 * Writes ours and the reference as PNG previews to test-output/quick-NAME-*.png.
 */
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { decodePfm } from '../src/cli/pfm';
import { encodePng } from '../src/cli/png';
import { blockMeans, meanValue, relativeMse, type LinearImage } from '../src/node/imageMetrics';
import { openRenderSession } from '../src/node/session';
import { parseSceneText } from '../src/scene/schema';

const FIXTURES = new URL('../test/fixtures/', import.meta.url);

function preview(image: LinearImage): Uint8Array {
  const out = new Uint8Array(image.width * image.height * 4);
  for (let p = 0; p < image.width * image.height; p++) {
    for (let c = 0; c < 3; c++) {
      const v = Math.min(1, Math.max(0, image.data[p * image.channels + c]));
      out[p * 4 + c] = Math.round(255 * (v <= 0.0031308 ? 12.92 * v : 1.055 * v ** (1 / 2.4) - 0.055));
    }
    out[p * 4 + 3] = 255;
  }
  return out;
}

async function main(argv: string[]): Promise<void> {
  const sppAt = argv.indexOf('--spp');
  const spp = sppAt >= 0 ? Number(argv[sppAt + 1]) : 64;
  const names = argv.filter((a, i) => a !== '--spp' && argv[i - 1] !== '--spp');
  const session = await openRenderSession();
  mkdirSync('test-output', { recursive: true });
  try {
    for (const name of names) {
      const scene = parseSceneText(readFileSync(new URL(`scenes/${name}.json`, FIXTURES), 'utf8'));
      const pfm = decodePfm(readFileSync(new URL(`references/${name}.pfm`, FIXTURES)));
      const reference: LinearImage = { width: pfm.width, height: pfm.height, channels: 3, data: pfm.rgb };
      await session.load(scene, { width: scene.image.width, height: scene.image.height, seed: 1 });
      const start = performance.now();
      await session.render(spp);
      const seconds = (performance.now() - start) / 1000;
      const ours: LinearImage = { width: scene.image.width, height: scene.image.height, channels: 4, data: await session.readLinear() };
      const worst = blockMeans(ours, 32).means.map((m, i) => m / (blockMeans(reference, 32).means[i] + 1e-3));
      console.log(
        `${name}: ${spp} spp in ${seconds.toFixed(1)} s, relMSE ${relativeMse(ours, reference).toExponential(2)}, ` +
          `mean ${meanValue(ours).toFixed(4)} vs ${meanValue(reference).toFixed(4)}, 32px block ratios ${Math.min(...worst).toFixed(3)}..${Math.max(...worst).toFixed(3)}`,
      );
      writeFileSync(`test-output/quick-${name}-ours.png`, encodePng(ours.width, ours.height, preview(ours)));
      writeFileSync(`test-output/quick-${name}-reference.png`, encodePng(reference.width, reference.height, preview(reference)));
    }
  } finally {
    await session.close();
  }
}

main(process.argv.slice(2)).catch((error) => {
  console.error(error);
  process.exit(1);
});
