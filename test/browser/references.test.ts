/**
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
import { loadFixtureScene, loadReference, renderLinear, useRenderSession } from '../support/browser';
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
/**
 * Total spp per scene; harder light transport gets more. Sized to what each
 * must show (2026-12-01, on this machine the test took 332 s): the largest
 * block sigma stays at most about 1.2% (the test requires under a third of
 * the worst-block bound). Measured at the counts before: 0.62% (glossy and
 * small-light at twice these), 0.81% (mirrors at 1.2x), 0.85%
 * (emissive-tilted-normals at twice, 32x32), 0.57% (instanced at twice) and
 * 0.80% (principled at twice); sigma grows as sqrt of the factor. `block` and
 * `worstBlock` override BLOCK and WORST_BLOCK where the noise is heavy-tailed
 * beyond what a CI-sized render can average in 16x16 blocks: in `bunny` the
 * ground under the faceted glass gem is lit only through refraction (glass
 * blocks shadow rays), found by BSDF sampling alone. Its 16x16 blocks keep
 * sigma ~4.7% at 512 spp; 32x32 blocks at 768 spp came to 1.78% (measured
 * 2026-12-01), at 640 spp about 1.95%, and the bound is 8% (4 sigma) with
 * the 6-sigma test unchanged.
 */
const SCENES: Record<string, { spp: number; block?: number; worstBlock?: number; referenceSpp?: number }> = {
  seed: { spp: 256 },
  glossy: { spp: 256 },
  'small-light': { spp: 128 },
  mirrors: { spp: 640 },
  glass: { spp: 512 },
  emissive: { spp: 256 },
  envmap: { spp: 768 },
  bunny: { spp: 640, block: 32, worstBlock: 0.08 },
  // Our own scene (scripts/make-reference.sh): an emissive mesh, sampled by next-event estimation.
  'emissive-mesh': { spp: 256 },
  // Ours too: an emissive quad whose vertex normals are tilted 37 degrees off
  // its face. Mitsuba converts a mesh light sample's area density to solid
  // angle with the shading normal's cosine; with the geometric one, the
  // ground under it came out 10-25% off (audit, bench/results/audit-v2-2026-11-28.md).
  'emissive-tilted-normals': { spp: 256, block: 32 },
  // Ours too: mesh instancing. ico-padded.ply (82k triangles: a coarse smooth
  // icosphere around a hidden dense one) is named by three meshes and stored
  // once, instanced (src/render/bvh/groups.ts); bunny.ply, named by three, is
  // too small and is copied per mesh (different rotations, uniform and
  // non-uniform scales, standard, glossy and dielectric materials), beside a
  // gem and a small emissive icosphere named once.
  instanced: { spp: 128 },
  // Version 3 (4096-spp references: twice the reference noise). Conductors:
  // named metals, given eta and k, smooth and rough, a rough tinted metal ground.
  conductor: { spp: 512, referenceSpp: 4096 },
  principled: { spp: 256, referenceSpp: 4096 },
  // Textures (baseColor, roughness and metallic from images, the uv
  // transform on the ground) and a normal map on a flat, unmirrored box.
  // 32x32 blocks: the reference's ground coordinates are off by up to 6e-3
  // units (the format's note: Mitsuba interpolates them in float over a
  // square 40000 units wide), which moves the checker's edges near the
  // camera by about half a pixel: at 1024 spp two 16x16 blocks there stayed
  // 3-4% off (a block holding two edges of full contrast), while every
  // 32x32 block came within 1.4% (at 256 spp the largest block sigma was 1.03%).
  textured: { spp: 128, block: 32, referenceSpp: 4096 },
  // Studio lights: a rectangle, a disk, a point, a spot and a directional
  // light over principled spheres, one a rough metal. The spot's and the
  // point's glints and caustics through the metal (alpha 0.04) are found by
  // next-event estimation at the metal vertex only and are heavy-tailed;
  // the spot's small share of the power (its emitter choice is 0.07) makes
  // them rarer and larger still. 32x32 blocks at 256 spp: the block on the
  // metal sphere's glint keeps sigma ~16% (measured 2026-12-02), every
  // other block at most 2.8%; so the bound on that block is loose (60%),
  // and the 6-sigma test on each block's own sigma is what binds. Each kind
  // alone is checked tightly by the light-<kind> scenes below.
  lights: { spp: 256, block: 32, worstBlock: 0.6, referenceSpp: 4096 },
  // Ours (scripts/make-reference.sh through the exporter): one light kind
  // each, over a Lambert ground and a Lambert and a glossy sphere, so a
  // broken kind fails by name. The rectangle is seen from the front, the
  // disk from behind (black), the spot's falloff lands on the ground.
  'light-rectangle': { spp: 128, referenceSpp: 4096 },
  'light-disk': { spp: 128, referenceSpp: 4096 },
  'light-point': { spp: 128, referenceSpp: 4096 },
  'light-spot': { spp: 128, referenceSpp: 4096 },
  'light-directional': { spp: 128, referenceSpp: 4096 },
};
const BATCHES = 8;

describe('convergence to the Mitsuba 3 references', () => {
  const session = useRenderSession();

  for (const [name, { spp, block: BLOCK = DEFAULT_BLOCK, worstBlock: WORST_BLOCK = DEFAULT_WORST_BLOCK, referenceSpp = 16384 }] of Object.entries(SCENES)) {
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
