/**
 * A/B of texts of scene/bvh.glsl on the traversal alone: the headless page's
 * BVH kernel (src/headless/bvhKernels.ts) traces a fixture scene's rays
 * (bench/bvhRays.ts: camera rays and bounces with closest hit, shadow rays
 * with any hit, one per pixel in image order) with each variant, the
 * variants alternating in one Chromium (the machine is shared). Prints the
 * fastest and median time of a draw per variant and kind of ray, and checks that every
 * variant finds the same hits as the first.
 *   npx tsx bench/bvh-kernel-ab.ts --variants base=src/shaders/scene/bvh.glsl,new=/tmp/bvh.glsl [--scene bunny] [--size 512x384] [--rounds 5] [--draws 4]
 * Variants must read the packed layout of this checkout's pack.ts (built into dist/web).
 */
import { readFileSync } from 'node:fs';
import { openRenderSession } from '../src/node/session';
import type { BvhTraceRequest } from '../src/headless/bvhKernels';
import { sceneRays, type BenchRay } from './bvhRays';
import { gpuProcessCpuSeconds } from './common';

const option = (name: string, fallback: string) => {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 ? process.argv[i + 1] : fallback;
};
const b64 = (a: Float32Array) => Buffer.from(a.buffer, a.byteOffset, a.byteLength).toString('base64');
const floats = (text: string) => {
  const bytes = Buffer.from(text, 'base64');
  return new Float32Array(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength));
};
const median = (v: number[]) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];
// The fastest draw: other load on the machine only ever slows a draw down.
const fastest = (v: number[]) => Math.min(...v);

const variants = option('variants', 'base=src/shaders/scene/bvh.glsl').split(',').map((v) => {
  const [name, file] = v.split('=');
  return { name, source: readFileSync(file, 'utf8') };
});
const [width, height] = option('size', '512x384').split('x').map(Number);
const rounds = Number(option('rounds', '5'));
const draws = Number(option('draws', '4'));
const rays = await sceneRays(option('scene', 'bunny'), width, height);
const kinds = [
  { name: 'camera', mode: 'closest', rays: rays.camera },
  { name: 'bounce', mode: 'closest', rays: rays.bounce },
  { name: 'shadow', mode: 'any', rays: rays.shadow },
] as const;
// A pixel without a ray gets one that misses everything (as a finished lane would cost little).
const data = (list: readonly (BenchRay | null)[]) => {
  const out = new Float32Array(list.length * 8);
  list.forEach((r, i) => out.set(r ? [...r.origin, 3.4e38, ...r.dir, 0] : [1e6, 1e6, 1e6, 3.4e38, 1, 0, 0, 0], i * 8));
  return b64(out);
};
const rayData = kinds.map((k) => data(k.rays));
const texture = b64(rays.packed.texture.data);

const session = await openRenderSession();
try {
  const trace = (request: BvhTraceRequest) => session.page.evaluate((r) => window.pathtraceBvh.trace(r), request);
  // Correctness: every variant's hits equal the first's.
  const reference: Float32Array[] = [];
  for (const [v, variant] of variants.entries()) {
    for (const [k, kind] of kinds.entries()) {
      const out = floats(await trace({ texture, rays: rayData[k], width, mode: kind.mode, bvhSource: variant.source }));
      if (v === 0) reference[k] = out;
      let wrong = 0;
      for (let i = 0; i < out.length / 4; i++) {
        const [a, b] = [reference[k].subarray(i * 4, i * 4 + 2), out.subarray(i * 4, i * 4 + 2)];
        const same = kind.mode === 'any' ? a[0] === b[0] : (a[0] < 0) === (b[0] < 0) && (a[0] < 0 || Math.abs(a[1] - b[1]) <= 1e-4 * a[1]);
        if (!same) wrong++;
      }
      if (v > 0) console.log(`${variant.name} ${kind.name}: ${wrong === 0 ? 'same hits' : `${wrong} DIFFERENT HITS`}`);
    }
  }
  const times = variants.map(() => kinds.map(() => [] as number[]));
  const cpu = variants.map(() => kinds.map(() => [] as number[]));
  for (let r = 0; r < rounds; r++) {
    const order = r % 2 ? [...variants.keys()].reverse() : [...variants.keys()];
    for (const v of order) {
      for (const [k, kind] of kinds.entries()) {
        const cpu0 = gpuProcessCpuSeconds() ?? NaN;
        times[v][k].push(Number(await trace({ texture, rays: rayData[k], width, mode: kind.mode, bvhSource: variants[v].source, timedDraws: draws })));
        // CPU time of the GPU process for the whole call (upload, 1 + draws draws, readback): load elsewhere barely changes it.
        cpu[v][k].push((((gpuProcessCpuSeconds() ?? NaN) - cpu0) * 1000) / (draws + 1));
      }
    }
  }
  for (const [v, variant] of variants.entries()) {
    const total = (f: (t: number[]) => number, w: number) => kinds.reduce((sum, _, k) => sum + f(times[w][k]), 0);
    console.log(
      `${variant.name.padEnd(14)} fastest: ${kinds.map((kind, k) => `${kind.name} ${fastest(times[v][k]).toFixed(1)}`).join(', ')}, total ${total(fastest, v).toFixed(1)} ms (x${(total(fastest, 0) / total(fastest, v)).toFixed(2)} speed); ` +
        `median total ${total(median, v).toFixed(1)} ms (x${(total(median, 0) / total(median, v)).toFixed(2)}); ` +
        `CPU per draw (median) ${kinds.map((kind, k) => `${kind.name} ${median(cpu[v][k]).toFixed(0)}`).join(', ')}, total ${kinds.reduce((sum, _, k) => sum + median(cpu[v][k]), 0).toFixed(0)} ms (x${(kinds.reduce((sum, _, k) => sum + median(cpu[0][k]), 0) / kinds.reduce((sum, _, k) => sum + median(cpu[v][k]), 0)).toFixed(2)})` +
        ` [${kinds.map((_, k) => times[v][k].map((t) => t.toFixed(0)).join(' ')).join(' | ')}]`,
    );
  }
} finally {
  await session.close();
}
