/**
 * Instancing (src/render/bvh/groups.ts) against copies, in the headless
 * renderer, interleaved in rounds so machine load hits both alike:
 *  - a row of K meshes of one file named as one file (stored once, K
 *    instances) and under K names (K world-space copies in one BVH): path
 *    rate and load time of each, for the bunny (test/fixtures/meshes/bunny.ply)
 *    and generated spheres of ~100k and ~1M triangles;
 *  - K meshes of one generated ~1M-triangle sphere: what is stored (triangles,
 *    BVH texture bytes) instanced and as copies, and the instanced path rate
 *    (as copies, more than two exceed the triangle limit).
 *   npx tsx bench/instancing.ts [--size 256x192] [--seconds 5] [--rounds 3] [--bunnies 3] [--spheres 4]
 */
import { readFileSync } from 'node:fs';
import { buildAndPackGroups } from '../src/render/bvh/worker';
import { MAX_TRIANGLES } from '../src/render/bvh/pack';
import { bvhInputs } from '../src/render/geometry/world';
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
    const groups = bvhInputs(scene, assets);
    const triangles = groups.flat().reduce((n, m) => n + m.indices.length / 3, 0);
    if (triangles > MAX_TRIANGLES) return { triangles, bytes: null, buildMs: null };
    const t0 = performance.now();
    const packed = buildAndPackGroups(groups);
    return { triangles, bytes: packed.texture.data.byteLength, buildMs: performance.now() - t0 };
  };
  const memory = { instanced: stored(false), copies: stored(true) };
  const mb = (b: number | null) => (b === null ? `over the ${MAX_TRIANGLES}-triangle limit` : `${(b / 2 ** 20).toFixed(0)} MB`);
  console.log(`${spheres} meshes of a ${sphere.indices.length / 3}-triangle file: instanced ${memory.instanced.triangles} triangles stored, ${mb(memory.instanced.bytes)}, BVH ${memory.instanced.buildMs?.toFixed(0)} ms; copies ${memory.copies.triangles} triangles, ${mb(memory.copies.bytes)}`);

  // Path rate, instanced against copies: K meshes of the bunny, of a ~100k and of a ~1M-triangle sphere.
  const cases = [
    // Under the threshold (groups.ts): both rows are copies, so this one shows the policy, not instancing.
    { name: `${k} bunnies (${bunny.indices.length / 3} triangles each, copied either way)`, file: 'bunny.ply', bytes: bunnyBytes, k, scale: 0.09 },
    { name: '3 spheres of ~100k triangles', file: 'sphere100k.ply', bytes: bumpySpherePly(100_000), k: 3, scale: 0.4 },
    { name: '2 spheres of ~1M triangles', file: 'sphere1m.ply', bytes: bumpySpherePly(1_000_000), k: 2, scale: 0.5 },
  ];
  const session = await openRenderSession();
  const results: Record<string, { instanced: { rate: number; loadMs: number }[]; copies: { rate: number; loadMs: number }[] }> = {};
  let sphereRate: { rate: number; loadMs: number } | null = null;
  try {
    for (let r = 0; r < rounds; r++) {
      for (const c of cases) {
        const shared = row(c.file, c.k, false, c.scale, width, height);
        const copies = row(c.file, c.k, true, c.scale, width, height);
        results[c.name] ??= { instanced: [], copies: [] };
        results[c.name].instanced.push(await rate(session, shared, filesFor(shared, c.bytes), seconds));
        results[c.name].copies.push(await rate(session, copies, filesFor(copies, c.bytes), seconds));
        const x = results[c.name];
        console.log(`round ${r + 1}, ${c.name}: instanced ${x.instanced[r].rate.toFixed(3)} M paths/s (load ${x.instanced[r].loadMs.toFixed(0)} ms), copies ${x.copies[r].rate.toFixed(3)} (load ${x.copies[r].loadMs.toFixed(0)} ms)`);
      }
    }
    const sphereScene = row('sphere.ply', spheres, false, 0.4, width, height);
    sphereRate = await rate(session, sphereScene, { 'sphere.ply': bumpySpherePly(1_000_000) }, seconds);
  } finally {
    await session.close();
  }
  const median = (v: number[]) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];
  console.log(`\n| ${width}x${height} | instanced M paths/s | copies M paths/s | instanced / copies (median of ${rounds} rounds) |\n|---|---|---|---|`);
  for (const [name, x] of Object.entries(results)) {
    const ratios = x.instanced.map((v, i) => v.rate / x.copies[i].rate);
    console.log(`| ${name} | ${median(x.instanced.map((v) => v.rate)).toFixed(3)} | ${median(x.copies.map((v) => v.rate)).toFixed(3)} | ${median(ratios).toFixed(2)} |`);
  }
  console.log(`\n${spheres} instances of the 1M-triangle sphere: ${sphereRate!.rate.toFixed(3)} M paths/s, load + first sample ${sphereRate!.loadMs.toFixed(0)} ms`);
  console.log(`saved ${writeResult('instancing', { width, height, seconds, rounds, spheres, memory, results, sphereRate })}`);
}

main().catch((error) => {
  console.error(error);
  process.exit(1);
});
