/**
 * Instancing (src/render/bvh/groups.ts) against copies, in the headless
 * renderer, interleaved in rounds so machine load hits both alike:
 *  - a row of K bunnies (test/fixtures/meshes/bunny.ply) named as one file
 *    (stored once, K instances) and under K spellings (K world-space copies
 *    in one BVH): path rate and load time of each;
 *  - K meshes of one generated ~1M-triangle sphere: what is stored (triangles,
 *    BVH texture bytes) instanced and as copies, and the instanced path rate
 *    (as copies, more than two exceed the triangle limit).
 *   npx tsx bench/instancing.ts [--size 256x192] [--seconds 5] [--rounds 3] [--bunnies 3] [--spheres 4]
 */
import { readFileSync } from 'node:fs';
import { buildAndPackGroups } from '../src/render/bvh/worker';
import { MAX_TRIANGLES } from '../src/render/bvh/pack';
import { bvhInputs } from '../src/render/passes/assetTextures';
import { openRenderSession, type RenderSession } from '../src/node/session';
import { decodeMesh } from '../src/scene/mesh';
import { parseScene } from '../src/scene/schema';
import type { Scene } from '../src/scene/types';
import { projectRoot, renderFor, writeResult } from './common';
import { bumpySphere, bumpySpherePly } from './meshGen';

const option = (name: string, fallback: string) => {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 && i + 1 < process.argv.length ? process.argv[i + 1] : fallback;
};

/** K meshes of `file` (or of `file` under K names when `copies`) in a row on the ground, each its own material. */
function row(file: string, k: number, copies: boolean, scale: number, width: number, height: number): Scene {
  return parseScene({
    version: 2,
    camera: { position: [0, 1.2, 5], target: [0, 0.4, 0], fov: 45 },
    image: { width, height },
    environment: { color: '#a0c0ff', intensity: 0.4 },
    ground: { height: 0, material: { color: [0.7, 0.7, 0.7], roughness: 1 } },
    lights: [{ position: [2, 4, 2], radius: 0.5, intensity: 40 }],
    meshes: Array.from({ length: k }, (_, i) => ({
      file: copies ? `${i}-${file}` : file,
      position: [(i - (k - 1) / 2) * (3.2 / k), 0, 0],
      rotation: [0, 25 * i, 0],
      scale,
      material: { color: [0.3 + (0.6 * i) / k, 0.5, 0.8 - (0.5 * i) / k], roughness: 0.2 + (0.6 * i) / k },
    })),
  });
}

const filesFor = (scene: Scene, bytes: Uint8Array) => Object.fromEntries(scene.meshes.map((m) => [m.file, bytes]));

async function rate(session: RenderSession, scene: Scene, files: Record<string, Uint8Array>, seconds: number) {
  const t0 = performance.now();
  await session.load(scene, { ...scene.image, seed: 1 }, files);
  await session.render(1);
  const loadMs = performance.now() - t0;
  const { spp, seconds: elapsed } = await renderFor(session, seconds, 1);
  return { rate: (spp * scene.image.width * scene.image.height) / elapsed / 1e6, loadMs };
}

async function main(): Promise<void> {
  const [width, height] = option('size', '256x192').split('x').map(Number);
  const seconds = Number(option('seconds', '5'));
  const rounds = Number(option('rounds', '3'));
  const k = Number(option('bunnies', '3'));
  const spheres = Number(option('spheres', '4'));
  const bunnyBytes = new Uint8Array(readFileSync(new URL('test/fixtures/meshes/bunny.ply', projectRoot())));
  const bunny = await decodeMesh(bunnyBytes, 'bunny.ply');

  // What is stored for K meshes of one 1M-triangle file.
  const sphere = bumpySphere(1_000_000);
  const stored = (copies: boolean) => {
    const scene = row('sphere.ply', spheres, copies, 0.4, width, height);
    const assets = { maps: new Map(), meshes: new Map(scene.meshes.map((m) => [m.file, sphere])) };
    const groups = bvhInputs(scene, assets, scene.meshes.map((_, i) => i));
    const triangles = groups.flat().reduce((n, m) => n + m.indices.length / 3, 0);
    if (triangles > MAX_TRIANGLES) return { triangles, bytes: null, buildMs: null };
    const t0 = performance.now();
    const packed = buildAndPackGroups(groups);
    return { triangles, bytes: packed.texture.data.byteLength, buildMs: performance.now() - t0 };
  };
  const memory = { instanced: stored(false), copies: stored(true) };
  const mb = (b: number | null) => (b === null ? `over the ${MAX_TRIANGLES}-triangle limit` : `${(b / 2 ** 20).toFixed(0)} MB`);
  console.log(`${spheres} meshes of a ${sphere.indices.length / 3}-triangle file: instanced ${memory.instanced.triangles} triangles stored, ${mb(memory.instanced.bytes)}, BVH ${memory.instanced.buildMs?.toFixed(0)} ms; copies ${memory.copies.triangles} triangles, ${mb(memory.copies.bytes)}`);

  const session = await openRenderSession();
  const results: Record<string, { rate: number; loadMs: number }[]> = { instanced: [], copies: [], spheres: [] };
  try {
    const shared = row('bunny.ply', k, false, 0.09, width, height);
    const copies = row('bunny.ply', k, true, 0.09, width, height);
    const sphereScene = row('sphere.ply', spheres, false, 0.4, width, height);
    const sphereFiles = { 'sphere.ply': bumpySpherePly(1_000_000) };
    for (let r = 0; r < rounds; r++) {
      results.instanced.push(await rate(session, shared, filesFor(shared, bunnyBytes), seconds));
      results.copies.push(await rate(session, copies, filesFor(copies, bunnyBytes), seconds));
      if (r === 0) results.spheres.push(await rate(session, sphereScene, sphereFiles, seconds));
      console.log(`round ${r + 1}: ${k} bunnies instanced ${results.instanced[r].rate.toFixed(3)} M paths/s, as copies ${results.copies[r].rate.toFixed(3)}`);
    }
  } finally {
    await session.close();
  }
  const median = (v: number[]) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];
  const ratios = results.instanced.map((x, i) => x.rate / results.copies[i].rate);
  console.log(`${k} bunnies (${bunny.indices.length / 3} triangles each) at ${width}x${height}: instanced / copies = ${median(ratios).toFixed(2)} (median of ${rounds} rounds; per round ${ratios.map((x) => x.toFixed(2)).join(', ')})`);
  console.log(`${spheres} instances of the 1M-triangle sphere: ${results.spheres[0].rate.toFixed(3)} M paths/s, load + first sample ${results.spheres[0].loadMs.toFixed(0)} ms`);
  console.log(`saved ${writeResult('instancing', { width, height, seconds, rounds, bunnies: k, spheres, memory, results, ratios })}`);
}

main().catch((error) => {
  console.error(error);
  process.exit(1);
});
