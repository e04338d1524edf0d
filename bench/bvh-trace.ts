/**
 * Rough figures for the GLSL BVH traversal on this machine (SwiftShader):
 * the kernel's compile time and closest-hit / any-hit rays per second for
 * primary rays over the bunny and over a ~1M-triangle mesh.
 * Run after `npm run build:web`: npx tsx bench/bvh-trace.ts [--bunny-only] [--web-root DIR]
 */
import { readFileSync } from 'node:fs';
import { openRenderSession } from '../src/node/session';
import { buildAndPack } from '../src/render/bvh/worker';
import type { BvhMeshInput } from '../src/render/bvh/build';
import { bvhBounds, type PackedBvh } from '../src/render/bvh/pack';
import { decodeMesh } from '../src/scene/mesh';
import { icosphere } from '../test/support/icosphere';

const b64 = (a: Float32Array) => Buffer.from(a.buffer, a.byteOffset, a.byteLength).toString('base64');

/** width x height rays from a point in front of the bounds, through a grid covering them. */
function primaryRays(packed: PackedBvh, width: number, height: number): Float32Array {
  const [lo, hi] = bvhBounds(packed);
  const c = [0, 1, 2].map((k) => (lo[k] + hi[k]) / 2);
  const size = Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  const eye = [c[0], c[1], c[2] + 2 * size];
  const rays = new Float32Array(width * height * 8);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const target = [c[0] + ((x + 0.5) / width - 0.5) * size * 1.2, c[1] + ((y + 0.5) / height - 0.5) * size * 0.9, c[2]];
      rays.set([...eye, 3.4e38, ...target.map((t, k) => t - eye[k]), 0], (y * width + x) * 8);
    }
  }
  return rays;
}

async function main(): Promise<void> {
  const rootArg = process.argv.indexOf('--web-root');
  const session = await openRenderSession(rootArg > 0 ? { webRoot: process.argv[rootArg + 1] } : {});
  try {
    const bunny = await decodeMesh(new Uint8Array(readFileSync(new URL('../test/fixtures/meshes/bunny.ply', import.meta.url))), 'bunny.ply');
    const scenes: [string, BvhMeshInput[]][] = [
      ['bunny (3674 triangles)', [{ ...bunny, material: 0 }]],
    ];
    if (!process.argv.includes('--bunny-only')) scenes.push(['icosphere level 8 (1.31M triangles)', [{ ...icosphere(8, true), material: 0 }]]);
    const [width, height] = [256, 192];
    for (const [name, meshes] of scenes) {
      const packed = buildAndPack(meshes);
      const rays = primaryRays(packed, width, height);
      // Large data goes to the page as the mesh, built there by the page's worker (as the app will).
      const mesh = meshes[0];
      const normals = mesh.normals ? b64(mesh.normals) : null;
      const built = await session.page.evaluate(([p, n, i]) => window.pathtraceBvh.buildInWorker(p, n, i, 0, true), [b64(mesh.positions), normals, b64(new Float32Array(mesh.indices.buffer))] as const);
      console.log(`${name}: built in the page's worker in ${built.milliseconds.toFixed(0)} ms (depth ${built.depth})`);
      for (const mode of ['closest', 'any', 'closest'] as const) {
        const request = { texture: '', rays: b64(rays), width, mode, timedDraws: 3 };
        const start = performance.now();
        const drawMs = Number(await session.page.evaluate((r) => window.pathtraceBvh.trace(r), request));
        const ms = performance.now() - start;
        console.log(`${name}, ${mode}: first call ${ms.toFixed(0)} ms (upload, compile the first time, 4 draws, readback); one draw of ${width * height} rays ${drawMs.toFixed(0)} ms = ${((width * height) / drawMs / 1000).toFixed(3)} Mrays/s`);
      }
    }
  } finally {
    await session.close();
  }
}

await main();
