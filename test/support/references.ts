/**
 * The check of a rendered scene against its Mitsuba 3 reference, shared by
 * the reference test files (test/browser/references*.test.ts: the scenes are
 * split over two files so that the test run renders them two at a time,
 * vitest.config.ts).
 *
 * Each shared scene against its Mitsuba 3 reference (16384 spp).
 *
 * Tolerances come from the noise measured in the same run, not from
 * hand-tuned percentages: the image is rendered as BATCHES independent
 * batches (different seeds). For every pixel, the sample variance of the
 * batch means over BATCHES estimates the variance of their average, so each
 * 16x16 block mean gets its own standard error sigma (several batches, not
 * two: a block whose noise comes from one pixel, such as the edge of a
 * light's reflection, needs a variance estimate with several degrees of
 * freedom, or it can come out near zero by chance). An unbiased renderer then lands within a few sigma of the
 * reference in every block (the reference's own noise, ~1% per pixel where
 * light is hard to reach, is 1/16 of that per block and is included as
 * REFERENCE_NOISE). We require:
 *   - every block within Z_MAX sigma (6: the noise of light found only by
 *     rare paths, such as mirror caustics on the ground, is heavy-tailed, so
 *     Gaussian false-alarm rates do not hold; 6 sigma over ~600
 *     block-channels still catches any bias above a fraction of a percent),
 *   - every block within WORST_BLOCK (a few percent) relative error, and
 *   - relMSE below 1.5x what the measured variance predicts (+ 1e-4).
 * The spp per scene is chosen so that sigma per block is well below the
 * few-percent bound; the test checks that too, so it cannot pass vacuously.
 * On failure, actual / expected / difference images go to test-output/.
 */
import { mkdirSync, writeFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { encodePfm } from '../../src/image/pfm';
import { average, blockMeans, compareBlocks, type LinearImage, meanValue, predictedRelMse, relativeMse, varianceOfMean } from '../../src/node/imageMetrics';
import { loadFixtureScene, loadReference, renderLinear, useRenderSession } from './browser';
import { cameraRay } from '../../src/scene/camera';
import type { Scene } from '../../src/scene/types';

const DEFAULT_BLOCK = 16;
const Z_MAX = 6;
const DEFAULT_WORST_BLOCK = 0.05;
/**
 * A known systematic difference of the references: Mitsuba's perspective
 * sensor clips at far_clip = 1e4, so in a sliver below the horizon the
 * references show the sky instead of the (infinite) ground plane. That moves
 * horizon blocks by up to ~0.7%; we allow 0.3% per block on top of the noise
 * (the absolute WORST_BLOCK bound still holds everywhere).
 */
const REFERENCE_SYSTEMATIC = 0.003;
/**
 * The same far clip, computed instead of estimated: the share of each pixel
 * whose camera ray meets the ground beyond far_clip, where the reference
 * shows the environment. On a bright ground under a dark map (bunny) the
 * horizon row alone moves a 32px block by ~3.5%; the z test allows each
 * block that share of the larger of the two images.
 */
const REFERENCE_FAR_CLIP = 1e4;

/** A scene's total spp and, where its noise needs them, its own block size, worst-block bound and its reference's spp. */
export interface ReferenceScene {
  spp: number;
  block?: number;
  worstBlock?: number;
  referenceSpp?: number;
}

const BATCHES = 8;

/** One test per scene (fixture scenes/<name>.json against references/<name>.pfm), in one browser. */
export function describeReferences(title: string, scenes: Record<string, ReferenceScene>): void {
  describe(title, () => {
    const session = useRenderSession();

    for (const [name, { spp, block: BLOCK = DEFAULT_BLOCK, worstBlock: WORST_BLOCK = DEFAULT_WORST_BLOCK, referenceSpp = 16384 }] of Object.entries(scenes)) {
      it(`${name} at ${spp} spp matches its reference within the measured noise`, async () => {
        // ~1% per pixel at 16384 spp, 1/BLOCK of that per block; noise grows as 1/sqrt(spp).
        const REFERENCE_NOISE = (0.01 / BLOCK) * Math.sqrt(16384 / referenceSpp);
        const scene = loadFixtureScene(name);
        const reference = loadReference(name);
        const batches: LinearImage[] = [];
        for (let seed = 1; seed <= BATCHES; seed++) batches.push(await renderLinear(session(), scene, spp / BATCHES, seed));
        const image = average(batches);
        const variance = varianceOfMean(batches, image);
        const floor = 0.02 * meanValue(reference);

        const sigma = blockMeans(variance, BLOCK).means.map((v) => Math.sqrt(v / (BLOCK * BLOCK)));
        const allowance = blockMeans(farClipAllowance(scene, image, reference), BLOCK).means;
        const refMeans = blockMeans(reference, BLOCK).means;
        const ourMeans = blockMeans(image, BLOCK).means;
        let worstZ = 0;
        let worstZBlock = '';
        let worstSigma = 0;
        for (let i = 0; i < refMeans.length; i++) {
          const scale = refMeans[i] + floor;
          const relSigma = Math.hypot(sigma[i] / scale, REFERENCE_NOISE, REFERENCE_SYSTEMATIC);
          worstSigma = Math.max(worstSigma, relSigma);
          const z = Math.max(0, Math.abs(ourMeans[i] - refMeans[i]) - allowance[i]) / scale / relSigma;
          if (z > worstZ) {
            const cols = Math.floor(image.width / BLOCK);
            const b = Math.floor(i / 3);
            worstZBlock = `block (${b % cols}, ${Math.floor(b / cols)}) channel ${i % 3}: ${ourMeans[i].toFixed(4)} vs ${refMeans[i].toFixed(4)}`;
          }
          worstZ = Math.max(worstZ, z);
        }
        const blocks = compareBlocks(image, reference, BLOCK, floor);
        const relMse = relativeMse(image, reference);
        const predicted = predictedRelMse(variance, reference);
        const report = `${name}: worst block ${(blocks.worst * 100).toFixed(2)}% (${worstZ.toFixed(2)} sigma at ${worstZBlock}), ` +
          `largest block sigma ${(worstSigma * 100).toFixed(2)}%, relMSE ${relMse.toExponential(3)} ` +
          `(noise predicts ${predicted.toExponential(3)})`;
        console.log(report);
        const ok = worstZ < Z_MAX && blocks.worst < WORST_BLOCK && relMse < 1.5 * predicted + 1e-4;
        if (!ok) writeFailureImages(name, image, reference);
        expect(worstSigma, 'noise too high for the tolerance to mean anything').toBeLessThan(WORST_BLOCK / 3);
        expect(worstZ, report).toBeLessThan(Z_MAX);
        expect(blocks.worst, report).toBeLessThan(WORST_BLOCK);
        expect(relMse, report).toBeLessThan(1.5 * predicted + 1e-4);
      }, 900_000);
    }
  });
}

/**
 * Per pixel and channel: the share of the pixel (4 x 16 sub-positions) whose
 * ray meets the ground further than REFERENCE_FAR_CLIP, times the larger of
 * our value and the reference's: the most the far clip can move that pixel.
 */
function farClipAllowance(scene: Scene, image: LinearImage, reference: LinearImage): LinearImage {
  const { width, height } = image;
  const data = new Float32Array(width * height * 3);
  const ground = scene.ground;
  if (!ground) return { width, height, channels: 3, data };
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      let beyond = 0;
      for (let sy = 0; sy < 16; sy++) {
        for (let sx = 0; sx < 4; sx++) {
          const ray = cameraRay(scene.camera, width / height, (x + (sx + 0.5) / 4) / width, (y + (sy + 0.5) / 16) / height);
          const t = (ground.height - ray.origin[1]) / ray.direction[1];
          if (t > REFERENCE_FAR_CLIP) beyond++;
        }
      }
      if (beyond === 0) continue;
      const p = y * width + x;
      for (let c = 0; c < 3; c++) {
        data[p * 3 + c] = (beyond / 64) * Math.max(Math.abs(image.data[p * image.channels + c]), Math.abs(reference.data[p * 3 + c]));
      }
    }
  }
  return { width, height, channels: 3, data };
}

function writeFailureImages(name: string, image: LinearImage, reference: LinearImage): void {
  const dir = new URL('../../test-output/', import.meta.url);
  mkdirSync(dir, { recursive: true });
  const rgba = (img: LinearImage, f: (p: number, c: number) => number) => {
    const out = new Float32Array(img.width * img.height * 4);
    for (let p = 0; p < img.width * img.height; p++) for (let c = 0; c < 3; c++) out[p * 4 + c] = f(p, c);
    return out;
  };
  const { width, height } = image;
  writeFileSync(new URL(`${name}.actual.pfm`, dir), encodePfm(width, height, rgba(image, (p, c) => image.data[p * 4 + c])));
  writeFileSync(new URL(`${name}.expected.pfm`, dir), encodePfm(width, height, rgba(reference, (p, c) => reference.data[p * 3 + c])));
  writeFileSync(
    new URL(`${name}.difference.pfm`, dir),
    encodePfm(width, height, rgba(image, (p, c) => Math.abs(image.data[p * 4 + c] - reference.data[p * 3 + c]))),
  );
}
