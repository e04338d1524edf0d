/**
 * Mitsuba 3's own glass white furnace, rendered once and committed as
 * fixtures for test/browser/glass-furnace.test.ts:
 *   npx tsx scripts/make-glass-furnace-fixtures.ts [--spp 4096]
 * For each roughness, the scene of glassFurnaceScene() (exported with
 * toMitsubaXml, as the benchmark does) is rendered by bench/mitsuba/render.py
 * twice with different seeds. test/fixtures/furnace-glass/r<r>.pfm is the
 * mean of the two; values.json gives per roughness the image mean and the
 * standard deviation of Mitsuba's 8x8 block means, estimated from the two
 * independent halves (sd of (a - b) / 2 over the blocks), so the test can
 * add Mitsuba's own noise to its tolerance.
 */
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { decodePfm, encodePfm } from '../src/image/pfm';
import { blockMeans, meanValue } from '../src/node/imageMetrics';
import { toMitsubaXml } from '../src/scene/mitsuba';
import { GLASS_FURNACE_ROUGHNESS, GLASS_FURNACE_SIZE, glassFurnaceScene } from '../test/support/glassFurnace';

const OUT = 'test/fixtures/furnace-glass';

function renderMitsuba(xml: string, seed: number, dir: string): Float32Array {
  const scenePath = join(dir, `scene-${seed}.xml`);
  const outPath = join(dir, `out-${seed}.pfm`);
  writeFileSync(scenePath, xml);
  const log = execFileSync('python3', ['bench/mitsuba/render.py', scenePath, '--out', outPath, '--seed', String(seed)], { encoding: 'utf8' });
  console.log(log.trim());
  return decodePfm(readFileSync(outPath)).rgb;
}

function main(argv: string[]): void {
  const sppAt = argv.indexOf('--spp');
  const spp = sppAt >= 0 ? Number(argv[sppAt + 1]) : 4096;
  const dir = mkdtempSync(join(tmpdir(), 'glass-furnace-'));
  const { width, height } = GLASS_FURNACE_SIZE;
  const values: Record<string, { mean: number; blockSigma: number; spp: number }> = {};
  for (const roughness of GLASS_FURNACE_ROUGHNESS) {
    const xml = toMitsubaXml(glassFurnaceScene(roughness), { spp, width, height });
    const [a, b] = [renderMitsuba(xml, 1, dir), renderMitsuba(xml, 1000003, dir)];
    const rgba = new Float32Array(width * height * 4);
    for (let p = 0; p < width * height; p++) for (let c = 0; c < 3; c++) rgba[p * 4 + c] = (a[p * 3 + c] + b[p * 3 + c]) / 2;
    writeFileSync(join(OUT, `r${roughness}.pfm`), encodePfm(width, height, rgba));
    const blocksA = blockMeans({ width, height, channels: 3, data: a }, 8).means;
    const blocksB = blockMeans({ width, height, channels: 3, data: b }, 8).means;
    let sumSq = 0;
    for (let i = 0; i < blocksA.length; i++) sumSq += (blocksA[i] - blocksB[i]) ** 2;
    const blockSigma = Math.sqrt(sumSq / blocksA.length) / 2;
    values[String(roughness)] = { mean: meanValue({ width, height, channels: 4, data: rgba }), blockSigma, spp: 2 * spp };
    console.log(roughness, values[String(roughness)]);
  }
  writeFileSync(join(OUT, 'values.json'), `${JSON.stringify(values, null, 2)}\n`);
}

main(process.argv.slice(2));
