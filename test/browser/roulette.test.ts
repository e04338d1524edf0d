/**
 * Russian roulette (an option, off by default) must not change the image's
 * expectation. The seed scene is rendered small with roulette on and off, in
 * batches with independent seeds; 4x4-pixel block means of the two must
 * agree within Z_MAX standard errors (estimated from the batches, both
 * renders' noise combined), and the image means within 0.5%. (Comparing with
 * the Mitsuba reference instead would mix in its known horizon artifact,
 * which the mirror sphere compresses into a few pixels at this size.)
 */
import { describe, expect, it } from 'vitest';
import { blockMeans, type LinearImage } from '../../src/node/imageMetrics';
import { loadFixtureScene, useRenderSession } from '../support/browser';

const SIZE = { width: 64, height: 48 };
const BATCHES = 6;
const SPP_PER_BATCH = 64;
const BLOCK = 4;
/** 5 sigma over 192 blocks x 3 channels: a false alarm below 1e-3 for Gaussian block errors. */
const Z_MAX = 5;

describe('Russian roulette', () => {
  const session = useRenderSession();

  async function batchBlockMeans(russianRoulette: boolean, firstSeed: number): Promise<Float64Array[]> {
    const scene = loadFixtureScene('seed');
    const out: Float64Array[] = [];
    for (let seed = firstSeed; seed < firstSeed + BATCHES; seed++) {
      await session().load(scene, { ...SIZE, seed, russianRoulette });
      await session().render(SPP_PER_BATCH);
      const image: LinearImage = { ...SIZE, channels: 4, data: await session().readLinear() };
      out.push(blockMeans(image, BLOCK).means);
    }
    return out;
  }

  it('leaves the expectation unchanged (seed scene, maxBounces 6)', async () => {
    const on = await batchBlockMeans(true, 1);
    const off = await batchBlockMeans(false, 101);
    const stats = (batches: Float64Array[], i: number) => {
      const mean = batches.reduce((a, b) => a + b[i], 0) / BATCHES;
      const variance = batches.reduce((a, b) => a + (b[i] - mean) ** 2, 0) / ((BATCHES - 1) * BATCHES);
      return { mean, variance };
    };
    let worstZ = 0;
    let sumOn = 0;
    let sumOff = 0;
    for (let i = 0; i < on[0].length; i++) {
      const a = stats(on, i);
      const b = stats(off, i);
      // A small absolute floor keeps exactly-deterministic blocks (sky) from dividing by zero.
      worstZ = Math.max(worstZ, Math.abs(a.mean - b.mean) / (Math.sqrt(a.variance + b.variance) + 1e-4));
      sumOn += a.mean;
      sumOff += b.mean;
    }
    expect(Math.abs(sumOn / sumOff - 1)).toBeLessThan(0.005);
    expect(worstZ).toBeLessThan(Z_MAX);
  });
});
