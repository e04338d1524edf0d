/**
 * Renders every version-1 fixture scene with a given build of the page at a
 * fixed size, spp and seed and writes the linear images as PFM fixtures:
 *   npx tsx scripts/make-v1-renders.ts OLD_CHECKOUT [OUT_DIR]
 * Made once with commit 60db06a (the last before the version-2
 * restructure): git worktree add --detach /tmp/old 60db06a; cd /tmp/old;
 * npm ci; npx vite build; then OLD_CHECKOUT = /tmp/old. The scene is parsed
 * by the old checkout's own parser and rendered by its page (dist/web).
 * test/browser/v1-bit-identical.test.ts renders the same with the current
 * build and requires bit-identical floats (PFM keeps float32 exactly).
 */
import { readFileSync, writeFileSync } from 'node:fs';
import { openRenderSession } from '../src/node/session';
import { resolve } from 'node:path';
import { encodePfm } from '../src/image/pfm';

/** Shared with the test, so both render exactly the same thing. */
export const V1_SCENES = ['seed', 'glossy', 'mirrors', 'small-light', 'furnace'] as const;
export const V1_RENDER = { width: 64, height: 48, spp: 4, seed: 11 } as const;

async function main(argv: string[]): Promise<void> {
  const [oldCheckout, outDir = 'test/fixtures/v1-renders'] = argv;
  if (!oldCheckout) throw new Error('usage: make-v1-renders.ts OLD_CHECKOUT [OUT_DIR]');
  const { parseSceneText } = (await import(resolve(oldCheckout, 'src/scene/schema.ts'))) as {
    parseSceneText: (text: string) => Parameters<typeof session.load>[0];
  };
  const session = await openRenderSession({ webRoot: resolve(oldCheckout, 'dist/web') });
  try {
    for (const name of V1_SCENES) {
      const scene = parseSceneText(readFileSync(`test/fixtures/scenes/${name}.json`, 'utf8'));
      await session.load(scene, { width: V1_RENDER.width, height: V1_RENDER.height, seed: V1_RENDER.seed });
      await session.render(V1_RENDER.spp);
      const rgba = await session.readLinear();
      writeFileSync(`${outDir}/${name}.pfm`, encodePfm(V1_RENDER.width, V1_RENDER.height, rgba));
      console.log(`${name}: written`);
    }
  } finally {
    await session.close();
  }
}

if (process.argv[1]?.endsWith('make-v1-renders.ts')) {
  main(process.argv.slice(2)).catch((error) => {
    console.error(error);
    process.exit(1);
  });
}
