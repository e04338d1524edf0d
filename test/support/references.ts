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
import { describe, expect, it } from 'vitest';
import { predictedRelMse, relativeMse, type LinearImage } from '../../src/node/imageMetrics';
import { loadFixtureScene, loadReference, renderLinear, useRenderSession } from './browser';
import { blockStats, summarize, writeFailureImages } from './referenceBlocks';

const DEFAULT_BLOCK = 16;
const Z_MAX = 6;
const DEFAULT_WORST_BLOCK = 0.05;

/** A scene's total spp and, where its noise needs them, its own block size, worst-block bound and its reference's spp. */
export interface ReferenceScene {
  spp: number;
  block?: number;
  worstBlock?: number;
  referenceSpp?: number;
  /** Render with adaptive sampling (PathTracerOptions.adaptive). */
  adaptive?: boolean;
}

const BATCHES = 8;

/** One test per scene (fixture scenes/<name>.json against references/<name>.pfm), in one browser. */
export function describeReferences(title: string, scenes: Record<string, ReferenceScene>): void {
  describe(title, () => {
    const session = useRenderSession();

    for (const [name, { spp, block: BLOCK = DEFAULT_BLOCK, worstBlock: WORST_BLOCK = DEFAULT_WORST_BLOCK, referenceSpp = 16384, adaptive = false }] of Object.entries(scenes)) {
      it(`${name} at ${spp} spp${adaptive ? ' (adaptive)' : ''} matches its reference within the measured noise`, async () => {
        const scene = loadFixtureScene(name);
        const reference = loadReference(name);
        const batches: LinearImage[] = [];
        // Independent batches (seeds): their spread is the estimator's, adaptive or not.
        for (let seed = 1; seed <= BATCHES; seed++) batches.push(await renderLinear(session(), scene, spp / BATCHES, seed, scene.image, adaptive));
        const stats = blockStats(scene, batches, reference, BLOCK, referenceSpp);
        const { image, variance } = stats;
        const { worstZ, worstZBlock, worstSigma, worstError } = summarize(stats);
        const relMse = relativeMse(image, reference);
        const predicted = predictedRelMse(variance, reference);
        const report = `${name}: worst block ${(worstError * 100).toFixed(2)}% (${worstZ.toFixed(2)} sigma at ${worstZBlock}), ` +
          `largest block sigma ${(worstSigma * 100).toFixed(2)}%, relMSE ${relMse.toExponential(3)} ` +
          `(noise predicts ${predicted.toExponential(3)})`;
        console.log(report);
        const ok = worstZ < Z_MAX && worstError < WORST_BLOCK && relMse < 1.5 * predicted + 1e-4;
        if (!ok) writeFailureImages(name, image, reference);
        expect(worstSigma, 'noise too high for the tolerance to mean anything').toBeLessThan(WORST_BLOCK / 3);
        expect(worstZ, report).toBeLessThan(Z_MAX);
        expect(worstError, report).toBeLessThan(WORST_BLOCK);
        expect(relMse, report).toBeLessThan(1.5 * predicted + 1e-4);
      }, 900_000);
    }
  });
}
