/**
 * Long accumulation: 100,000 samples per pixel on a tiny image. The running
 * sums are float32, so they lose low bits once they are large; the sample
 * index and the seed feed a counter-based hash, so streams must not repeat or
 * band after many samples. Checked here:
 *
 * - the long run's mean agrees with short runs of other seeds within their
 *   noise (no drift);
 * - pixels that see only the constant sky keep their exact value to 2e-3
 *   (float32 rounding of a constant summand is the worst case: ~1e-3 at 1e5);
 * - two long runs with independent seeds differ by what 1/sqrt(N) predicts
 *   from the short runs' spread: if the random streams repeated with some
 *   period P, the long runs would only be as good as P samples.
 */
import { describe, expect, it } from 'vitest';
import { parseScene } from '../../src/scene/schema';
import { useRenderSession } from '../support/browser';

const SIZE = { width: 8, height: 8 };
const LONG = 100_000;
const SHORT = 1_000;
const SKY = 0.55;

// Upper rows see the constant sky (exactly SKY); lower rows see a diffuse
// sphere and ground lit by the sky only (cheap, and noisy).
const scene = parseScene({
  camera: { position: [0, 1, 4], target: [0, 1.2, 0], fov: 40 },
  render: { maxBounces: 3 },
  environment: { color: [1, 1, 1], intensity: SKY },
  ground: { height: 0, material: { color: [0.6, 0.6, 0.6], roughness: 1 } },
  spheres: [{ center: [0, 0.5, 0], radius: 0.8, material: { color: [0.8, 0.5, 0.3], roughness: 0.7 } }],
});

const luminance = (data: Float32Array, p: number) => (data[p * 4] + data[p * 4 + 1] + data[p * 4 + 2]) / 3;
const mean = (xs: number[]) => xs.reduce((a, b) => a + b, 0) / xs.length;
const rms = (a: Float32Array, b: Float32Array, pixels: number[]) =>
  Math.sqrt(mean(pixels.map((p) => (luminance(a, p) - luminance(b, p)) ** 2)));

describe('long accumulation (100k spp)', () => {
  const session = useRenderSession();

  async function renderRun(spp: number, seed: number): Promise<Float32Array> {
    await session().load(scene, { ...SIZE, seed });
    expect(await session().render(spp)).toBe(spp);
    const data = await session().readLinear();
    for (let p = 0; p < SIZE.width * SIZE.height; p++) expect(data[p * 4 + 3], 'rejected samples').toBe(0);
    return data;
  }

  it('agrees with short runs, keeps constant pixels exact and converges as 1/sqrt(N)', async () => {
    const shorts: Float32Array[] = [];
    for (const seed of [11, 12, 13, 14]) shorts.push(await renderRun(SHORT, seed));
    const longA = await renderRun(LONG, 1);
    const longB = await renderRun(LONG, 2);

    const pixels = Array.from({ length: SIZE.width * SIZE.height }, (_, p) => p);
    // Constant pixels: every short run sees exactly the sky there.
    const sky = pixels.filter((p) => shorts.every((s) => Math.abs(luminance(s, p) / SKY - 1) < 1e-4));
    const noisy = pixels.filter((p) => shorts.some((s) => Math.abs(luminance(s, p) - SKY) > 1e-3));
    expect(sky.length, 'the scene has sky pixels').toBeGreaterThan(8);
    expect(noisy.length, 'the scene has noisy pixels').toBeGreaterThan(16);

    // 1. Constant pixels after 1e5 additions of float32 SKY: float rounding only.
    for (const p of sky) {
      expect(Math.abs(luminance(longA, p) / SKY - 1), `sky pixel ${p}`).toBeLessThan(2e-3);
    }

    // 2. The image mean of the long run against the short runs' mean and spread.
    const imageMean = (d: Float32Array) => mean(pixels.map((p) => luminance(d, p)));
    const shortMeans = shorts.map(imageMean);
    const shortMean = mean(shortMeans);
    const shortSd = Math.sqrt(shortMeans.reduce((a, m) => a + (m - shortMean) ** 2, 0) / (shortMeans.length - 1));
    // Standard error of the 4-run average, floored: 4 runs give a rough sd.
    const tolerance = 4 * Math.max(shortSd / 2, 1e-3 * shortMean);
    expect(Math.abs(imageMean(longA) - shortMean), `long ${imageMean(longA)} vs short ${shortMean} +- ${shortSd}`).toBeLessThan(tolerance);
    expect(Math.abs(imageMean(longB) - shortMean)).toBeLessThan(tolerance);

    // 3. Convergence: rms difference of two independent runs is sigma * sqrt(2 / N).
    // Short pairs estimate sigma; the long pair must shrink by sqrt(LONG / SHORT) = 10.
    const shortPairs = [rms(shorts[0], shorts[1], noisy), rms(shorts[2], shorts[3], noisy)];
    const expectedLong = mean(shortPairs) * Math.sqrt(SHORT / LONG);
    const actualLong = rms(longA, longB, noisy);
    expect(actualLong, `long-run rms diff ${actualLong}, expected ~${expectedLong}`).toBeLessThan(2 * expectedLong);
    expect(actualLong).toBeGreaterThan(expectedLong / 3); // different seeds really are different streams

    // 4. A single pixel: the long estimate against another seed's, within 5 sigma.
    const p = noisy[Math.floor(noisy.length / 2)];
    const sigmaPixel = Math.sqrt(mean(shorts.map((s) => (luminance(s, p) - mean(shorts.map((t) => luminance(t, p)))) ** 2)) * 4 / 3);
    const sigmaLong = sigmaPixel * Math.sqrt(SHORT / LONG);
    expect(Math.abs(luminance(longA, p) - luminance(longB, p))).toBeLessThan(5 * Math.SQRT2 * Math.max(sigmaLong, 1e-4));
  });
});
