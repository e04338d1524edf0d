/**
 * The noise-derived block test of a render against a Mitsuba reference
 * (test/browser/references.test.ts explains the statistics): per block and
 * channel, the distance between our block mean and the reference's in
 * sigmas of the noise measured over independent batches, and the relative
 * error. `summarize` reduces it over all blocks or over a region's blocks,
 * so a scene can be checked region by region (a model's primitives).
 */
import { mkdirSync, writeFileSync } from 'node:fs';
import { encodePfm } from '../../src/image/pfm';
import { average, blockMeans, type LinearImage, meanValue, varianceOfMean } from '../../src/node/imageMetrics';
import { cameraRay } from '../../src/scene/camera';
import type { Scene } from '../../src/scene/types';

/**
 * A known systematic difference of the references: Mitsuba's perspective
 * sensor clips at far_clip = 1e4, so in a sliver below the horizon the
 * references show the sky instead of the (infinite) ground plane. That moves
 * horizon blocks by up to ~0.7%; we allow 0.3% per block on top of the noise
 * (the absolute worst-block bound still holds everywhere).
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

export interface BlockStats {
  block: number;
  cols: number;
  rows: number;
  image: LinearImage;
  variance: LinearImage;
  /** Per block and channel: |ours - reference| beyond the far-clip allowance, in sigmas. */
  z: Float64Array;
  /** Per block and channel: the relative sigma (noise, reference noise, systematic). */
  relSigma: Float64Array;
  /** Per block and channel: |ours - reference| / (reference + floor). */
  relError: Float64Array;
  ours: Float64Array;
  reference: Float64Array;
}

/** The block statistics of the batches' average against the reference (referenceSpp: its sample count, for its own noise). */
export function blockStats(scene: Scene, batches: LinearImage[], reference: LinearImage, block: number, referenceSpp: number): BlockStats {
  // ~1% per pixel at 16384 spp, 1/block of that per block; noise grows as 1/sqrt(spp).
  const referenceNoise = (0.01 / block) * Math.sqrt(16384 / referenceSpp);
  const image = average(batches);
  const variance = varianceOfMean(batches, image);
  const floor = 0.02 * meanValue(reference);
  const sigma = blockMeans(variance, block).means.map((v) => Math.sqrt(v / (block * block)));
  const allowance = blockMeans(farClipAllowance(scene, image, reference), block).means;
  const { cols, rows, means: refMeans } = blockMeans(reference, block);
  const ourMeans = blockMeans(image, block).means;
  const n = refMeans.length;
  const [z, relSigma, relError] = [new Float64Array(n), new Float64Array(n), new Float64Array(n)];
  for (let i = 0; i < n; i++) {
    const scale = refMeans[i] + floor;
    relSigma[i] = Math.hypot(sigma[i] / scale, referenceNoise, REFERENCE_SYSTEMATIC);
    z[i] = Math.max(0, Math.abs(ourMeans[i] - refMeans[i]) - allowance[i]) / scale / relSigma[i];
    relError[i] = Math.abs(ourMeans[i] - refMeans[i]) / scale;
  }
  return { block, cols, rows, image, variance, z, relSigma, relError, ours: ourMeans, reference: refMeans };
}

export interface BlockSummary {
  worstZ: number;
  worstZBlock: string;
  worstSigma: number;
  worstError: number;
  blocks: number;
}

/** The worst z, sigma and relative error over the given blocks (indices into cols x rows; all when omitted). */
export function summarize(stats: BlockStats, blocks?: Iterable<number>): BlockSummary {
  const out: BlockSummary = { worstZ: 0, worstZBlock: '', worstSigma: 0, worstError: 0, blocks: 0 };
  const list = blocks ? [...blocks] : Array.from({ length: stats.cols * stats.rows }, (_, b) => b);
  for (const b of list) {
    out.blocks++;
    for (let c = 0; c < 3; c++) {
      const i = b * 3 + c;
      out.worstSigma = Math.max(out.worstSigma, stats.relSigma[i]);
      out.worstError = Math.max(out.worstError, stats.relError[i]);
      if (stats.z[i] > out.worstZ) {
        out.worstZ = stats.z[i];
        out.worstZBlock = `block (${b % stats.cols}, ${Math.floor(b / stats.cols)}) channel ${c}: ${stats.ours[i].toFixed(4)} vs ${stats.reference[i].toFixed(4)}`;
      }
    }
  }
  return out;
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

/** Actual, expected and difference images of a failed comparison, in test-output/. */
export function writeFailureImages(name: string, image: LinearImage, reference: LinearImage): void {
  const dir = new URL('../../test-output/', import.meta.url);
  mkdirSync(dir, { recursive: true });
  const rgba = (img: LinearImage, f: (p: number, c: number) => number) => {
    const out = new Float32Array(img.width * img.height * 4);
    for (let p = 0; p < img.width * img.height; p++) for (let c = 0; c < 3; c++) out[p * 4 + c] = f(p, c);
    return out;
  };
  const { width, height } = image;
  writeFileSync(new URL(`${name}.actual.pfm`, dir), encodePfm(width, height, rgba(image, (p, c) => image.data[p * image.channels + c])));
  writeFileSync(new URL(`${name}.expected.pfm`, dir), encodePfm(width, height, rgba(reference, (p, c) => reference.data[p * 3 + c])));
  writeFileSync(
    new URL(`${name}.difference.pfm`, dir),
    encodePfm(width, height, rgba(image, (p, c) => Math.abs(image.data[p * image.channels + c] - reference.data[p * 3 + c]))),
  );
}
