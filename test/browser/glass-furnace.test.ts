/**
 * The glass white furnace: a dielectric sphere (ior 1.5) in a uniform white
 * environment, no ground, no lights, 64 bounces (test/support/glassFurnace.ts).
 * - Smooth glass with tint 1 conserves energy: every pixel's expected value
 *   is 1 (up to paths still inside after 64 bounces, far below the noise).
 * - Rough glass loses energy (single-scattering GGX); the amount must be
 *   Mitsuba 3's own, from fixtures rendered once by
 *   scripts/make-glass-furnace-fixtures.ts (4096 spp, with its noise).
 * - A tint < 1 darkens the sphere.
 * Tolerances come from the noise measured in the test itself: each image is
 * rendered with two independent seeds a and b; E[((a - b) / 2)^2] is the
 * variance of their average per pixel, so each 8x8 block's sigma is
 * sqrt(sum over its pixels of ((a - b) / 2)^2) / 64 (64 degrees of freedom;
 * per block, because blocks on the silhouette are much noisier than the
 * sky). Mitsuba's block noise (pooled over blocks, 16x smaller than ours)
 * is in the fixtures' values.json. Blocks must agree within 5 sigma (with
 * 64 blocks a false failure has probability ~4e-5), the image mean within 5
 * sigma of the mean of 64 blocks.
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { decodePfm } from '../../src/image/pfm';
import { blockMeans, type LinearImage } from '../../src/node/imageMetrics';
import type { RenderSession } from '../../src/node/session';
import type { Vec3 } from '../../src/scene/types';
import { FIXTURES, renderLinear, useRenderSession } from '../support/browser';
import { GLASS_FURNACE_ROUGHNESS, GLASS_FURNACE_SIZE, glassFurnaceScene } from '../support/glassFurnace';

const SPP = 32; // per seed; two seeds
const BLOCK = 8;
const SIGMAS = 5;

interface NoisyBlocks { means: Float64Array; sigmas: Float64Array; sigma: number }

/** Grey 8x8 block means of the average of two seeds' renders, each block's noise, and the largest. */
async function renderBlocks(session: RenderSession, roughness: number, color: Vec3 = [1, 1, 1]): Promise<NoisyBlocks> {
  const scene = glassFurnaceScene(roughness, color);
  const [a, b] = [await renderLinear(session, scene, SPP, 1, GLASS_FURNACE_SIZE), await renderLinear(session, scene, SPP, 2, GLASS_FURNACE_SIZE)];
  const { width, height } = GLASS_FURNACE_SIZE;
  const average = new Float32Array(width * height * 4);
  const halfDifferenceSq = new Float32Array(width * height * 4);
  for (let p = 0; p < width * height; p++) {
    const grey = (image: LinearImage) => (image.data[p * 4] + image.data[p * 4 + 1] + image.data[p * 4 + 2]) / 3;
    average[p * 4] = (grey(a) + grey(b)) / 2;
    halfDifferenceSq[p * 4] = ((grey(a) - grey(b)) / 2) ** 2;
  }
  const means = blockMeans({ width, height, channels: 4, data: average }, BLOCK, 1).means;
  // blockMeans divides by 64 once; the variance of a block mean needs 64^2.
  const sigmas = blockMeans({ width, height, channels: 4, data: halfDifferenceSq }, BLOCK, 1).means.map((v) => Math.sqrt(v / (BLOCK * BLOCK)));
  return { means, sigmas, sigma: Math.max(...sigmas) };
}

function greyBlocks(image: LinearImage): Float64Array {
  const rgb = blockMeans(image, BLOCK).means;
  return Float64Array.from({ length: rgb.length / 3 }, (_, i) => (rgb[i * 3] + rgb[i * 3 + 1] + rgb[i * 3 + 2]) / 3);
}

const mean = (values: Float64Array) => values.reduce((s, v) => s + v, 0) / values.length;

describe('glass white furnace', () => {
  const session = useRenderSession();

  it('smooth glass, tint 1, renders 1 everywhere within noise', async () => {
    const { means, sigmas, sigma } = await renderBlocks(session(), 0);
    const summary = JSON.stringify({ mean: mean(means), sigma, min: Math.min(...means), max: Math.max(...means) });
    console.log(`smooth glass furnace: ${summary}`);
    // A floor of 1e-4 on sigma: if the render were noise-free, float rounding.
    for (let b = 0; b < means.length; b++) expect(Math.abs(means[b] - 1), `block ${b}: ${summary}`).toBeLessThan(SIGMAS * Math.max(sigmas[b], 1e-4));
    const meanSigma = Math.hypot(...sigmas) / means.length;
    expect(Math.abs(mean(means) - 1), summary).toBeLessThan(SIGMAS * Math.max(meanSigma, 1e-5));
  });

  const fixtureValues = JSON.parse(readFileSync(new URL('furnace-glass/values.json', FIXTURES), 'utf8')) as Record<string, { mean: number; blockSigma: number }>;
  for (const roughness of GLASS_FURNACE_ROUGHNESS) {
    it(`rough glass r = ${roughness} matches Mitsuba's furnace`, async () => {
      const reference = decodePfm(readFileSync(new URL(`furnace-glass/r${roughness}.pfm`, FIXTURES)));
      const referenceBlocks = greyBlocks({ width: reference.width, height: reference.height, channels: 3, data: reference.rgb });
      const { means, sigmas, sigma } = await renderBlocks(session(), roughness);
      const mitsubaSigma = fixtureValues[String(roughness)].blockSigma;
      const combined = Math.hypot(sigma, mitsubaSigma);
      let worst = 0;
      for (let b = 0; b < means.length; b++) worst = Math.max(worst, Math.abs(means[b] - referenceBlocks[b]) / Math.hypot(sigmas[b], mitsubaSigma));
      const meanSigma = Math.hypot(Math.hypot(...sigmas) / means.length, mitsubaSigma / Math.sqrt(means.length));
      const centre = (means.length / 2) + Math.sqrt(means.length) / 2; // a block on the sphere
      const summary = JSON.stringify({
        mean: mean(means), mitsuba: mean(referenceBlocks), sigma, combined, worstSigmas: worst,
        centre: means[centre], mitsubaCentre: referenceBlocks[centre],
      });
      console.log(`rough glass furnace r=${roughness}: ${summary}`);
      expect(worst, summary).toBeLessThan(SIGMAS);
      expect(Math.abs(mean(means) - mean(referenceBlocks)), summary).toBeLessThan(SIGMAS * meanSigma);
      // The fixture itself: energy is lost on the sphere, more with roughness.
      expect(referenceBlocks[centre]).toBeLessThan(1);
    });
  }

  it('a tint < 1 darkens the sphere', async () => {
    // Untinted smooth glass renders 1 (the first test); tinted must be darker.
    const tinted = await renderBlocks(session(), 0, [0.7, 0.7, 0.7]);
    const centre = tinted.means.length / 2 + Math.sqrt(tinted.means.length) / 2;
    const summary = JSON.stringify({ tinted: tinted.means[centre], sigma: tinted.sigmas[centre] });
    console.log(`tint: ${summary}`);
    expect(tinted.means[centre], summary).toBeLessThan(1 - SIGMAS * tinted.sigmas[centre]);
    // Light through the centre crosses the boundary twice: about 0.7^2 of it,
    // plus the untinted Fresnel reflection (~4%).
    expect(tinted.means[centre], summary).toBeLessThan(0.6);
    expect(tinted.means[centre], summary).toBeGreaterThan(0.4);
  });
});
