/**
 * Work per ray of the BVH traversal, counted by the TypeScript mirror
 * (src/render/bvh/traverse.ts) on a scene's meshes: loop steps (nodes and
 * triangles) and stack pops per ray, and steps per 2x2 pixel quad in lock
 * step (SwiftShader runs a quad's 4 lanes together: a loop runs as long as
 * its slowest lane). Rays: the camera's (one per pixel, no
 * jitter), then from each camera hit on a mesh or the ground a cosine
 * direction (closest hit) and a shadow ray to a uniform upper-hemisphere
 * direction (any hit).
 * A step is a node visit or a leaf step (one triangle in the binary BVH, up
 * to two in the wide one): "triangles" counts the triangles tested.
 *   npx tsx bench/bvh-stats.ts [--scene bunny|FILE.json] [--size 128x96]
 */
import { traceStats, type TraceStats } from '../src/render/bvh/traverse';
import { sceneRays } from './bvhRays';

const option = (name: string, fallback: string) => {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 ? process.argv[i + 1] : fallback;
};

const [width, height] = option('size', '128x96').split('x').map(Number);
const t0 = performance.now();
const rays = await sceneRays(option('scene', 'bunny'), width, height);
const { packed } = rays;
console.log(`${packed.triangleCount} triangles, ${packed.nodeCount} nodes, depth ${packed.depth}; rays in ${(performance.now() - t0).toFixed(0)} ms`);

type Kind = 'camera' | 'bounce' | 'shadow';
const stats: Record<Kind, TraceStats[][]> = { camera: [], bounce: [], shadow: [] };
for (let y = 0; y < height; y += 2) {
  for (let x = 0; x < width; x += 2) {
    const quad: Record<Kind, TraceStats[]> = { camera: [], bounce: [], shadow: [] };
    for (const [dx, dy] of [[0, 0], [1, 0], [0, 1], [1, 1]]) {
      const i = (y + dy) * width + x + dx;
      for (const kind of ['camera', 'bounce', 'shadow'] as const) {
        const ray = rays[kind][i];
        if (ray) quad[kind].push(traceStats(packed, ray.origin, ray.dir, Infinity, kind === 'shadow'));
      }
    }
    for (const k of Object.keys(quad) as Kind[]) if (quad[k].length) stats[k].push(quad[k]);
  }
}

const mean = (v: number[]) => v.reduce((a, b) => a + b, 0) / Math.max(1, v.length);
for (const kind of Object.keys(stats) as Kind[]) {
  const quads = stats[kind];
  const all = quads.flat();
  const field = (f: (s: TraceStats) => number) => mean(all.map(f)).toFixed(2);
  // Lock step: a quad runs as many steps as its slowest lane.
  const quadSteps = mean(quads.map((q) => Math.max(...q.map((s) => s.steps.length))));
  const raySteps = mean(all.map((s) => s.steps.length));
  const touching = all.filter((s) => s.hit || s.steps.length > 1).length;
  console.log(
    `${kind}: ${all.length} rays (${((100 * touching) / all.length).toFixed(0)}% go past the root); per ray: ${raySteps.toFixed(2)} steps, ` +
      `${field((s) => s.steps.filter((c) => c === 0).length)} nodes, ${field((s) => s.steps.filter((c) => c > 0).length)} triangle steps, ${field((s) => s.steps.reduce((a, c) => a + c, 0))} triangles, ${field((s) => s.pops)} pops; ` +
      `per quad in lock step: ${quadSteps.toFixed(2)} steps (${(quadSteps / Math.max(1e-9, raySteps)).toFixed(2)}x the mean ray's)`,
  );
}
