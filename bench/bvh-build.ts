/**
 * BVH build time and memory in Node, for the report: the bunny
 * (test/fixtures/meshes/bunny.ply and the npm package `bunny`, 3674
 * triangles each) and a generated mesh of about 1M triangles (a bumpy
 * sphere, smooth). Run: node --expose-gc --import tsx bench/bvh-build.ts [--triangles N]
 */
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { buildBvh, type BvhMeshInput } from '../src/render/bvh/build';
import { packBvh } from '../src/render/bvh/pack';
import { decodeMesh } from '../src/scene/mesh';
import { bumpySphere as bumpySphereMesh } from './meshGen';

const gc = (globalThis as { gc?: () => void }).gc ?? (() => {});
const mb = (bytes: number) => `${(bytes / 2 ** 20).toFixed(1)} MB`;

/** The bumpy sphere of bench/meshGen.ts (the mesh benchmarks share it), carrying material 0. */
const bumpySphere = (triangles: number): BvhMeshInput => ({ ...bumpySphereMesh(triangles), material: 0 });

function measure(name: string, meshes: BvhMeshInput[]): void {
  gc();
  const before = process.memoryUsage();
  // CPU time as well as wall time: the machine is shared, and CPU time is what the build itself costs.
  const cpu0 = process.cpuUsage();
  const t0 = performance.now();
  const bvh = buildBvh(meshes);
  const t1 = performance.now();
  const cpu1 = process.cpuUsage(cpu0);
  const packed = packBvh(bvh, meshes);
  const t2 = performance.now();
  const after = process.memoryUsage();
  const triangles = packed.triangleCount;
  const textureBytes = packed.texture.data.byteLength;
  console.log(
    `${name}: ${triangles} triangles, ${packed.nodeCount} nodes, depth ${packed.depth}; ` +
      `build ${(t1 - t0).toFixed(0)} ms wall, ${((cpu1.user + cpu1.system) / 1000).toFixed(0)} ms CPU; pack ${(t2 - t1).toFixed(0)} ms; ` +
      `texture ${mb(textureBytes)} (${packed.texture.width}x${packed.texture.height}x${packed.texture.layers}); ` +
      `heap+arrays grew ${mb(after.heapUsed + after.arrayBuffers - before.heapUsed - before.arrayBuffers)}, rss ${mb(after.rss)}`,
  );
}

async function main(): Promise<void> {
  const arg = process.argv.indexOf('--triangles');
  const big = arg > 0 ? Number(process.argv[arg + 1]) : 1_000_000;
  const fixture = await decodeMesh(new Uint8Array(readFileSync(new URL('../test/fixtures/meshes/bunny.ply', import.meta.url))), 'bunny.ply');
  const npmBunny = createRequire(import.meta.url)('bunny') as { positions: number[][]; cells: number[][] };
  const fromNpm = { positions: Float32Array.from(npmBunny.positions.flat()), normals: null, indices: Uint32Array.from(npmBunny.cells.flat()), material: 0 };
  for (let round = 0; round < 2; round++) {
    // The first round includes JIT warm-up; the second is the steady figure.
    measure(`bunny.ply (round ${round + 1})`, [{ ...fixture, material: 0 }]);
    measure(`npm bunny (round ${round + 1})`, [fromNpm]);
  }
  measure(`bumpy sphere`, [bumpySphere(big)]);
}

await main();
