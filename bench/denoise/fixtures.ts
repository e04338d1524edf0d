/**
 * Makes test/fixtures/denoise/seed-{albedo,normal}.pfm: Mitsuba 3 guides
 * (bench/denoise/guides.py, 64 spp) of the seed scene at its 256x192, for
 * test/browser/denoise.test.ts until the tracer has its own AOVs.
 *
 *   npx tsx bench/denoise/fixtures.ts
 */
import { copyFileSync, mkdirSync, readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { parseSceneText } from '../../src/scene/schema';
import { projectRoot } from '../common';
import { mitsubaGuides } from './guides';

const root = projectRoot();
const scene = parseSceneText(readFileSync(new URL('test/fixtures/scenes/seed.json', root), 'utf8'));
const { width, height } = scene.image;
const spp = 64;
mitsubaGuides(root, 'seed', scene, width, height, spp);
const out = fileURLToPath(new URL('test/fixtures/denoise/', root));
mkdirSync(out, { recursive: true });
for (const kind of ['albedo', 'normal']) {
  copyFileSync(fileURLToPath(new URL(`bench/scratch/denoise/seed-${width}x${height}-${spp}-${kind}.pfm`, root)), `${out}seed-${kind}.pfm`);
}
console.log(`wrote ${out}seed-albedo.pfm, seed-normal.pfm (${width}x${height}, ${spp} spp)`);
