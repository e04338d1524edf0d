/**
 * How many BVH traversal steps a path costs in the real renderer: the page's
 * own trace shader for a scene, patched to count, per pixel, the steps
 * (loop iterations) and calls of closest-hit and any-hit traversals, and to
 * write those counts instead of radiance; rendered for a few samples and
 * read back. Prints per sample: steps and calls of each kind, steps per
 * call, and the per-quad maximum (SwiftShader runs a pixel quad in lock step,
 * so a quad costs at least its busiest lane's steps).
 *   npx tsx bench/bvh-steps.ts [--scene bunny] [--size 512x384] [--spp 4]
 * Needs dist/web built from this checkout (the patch finds bvh.glsl's loop by its text).
 */
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { openRenderSession, type LoadOptions } from '../src/node/session';
import { readSceneFiles } from '../src/node/sceneFiles';
import { parseSceneText } from '../src/scene/schema';
import { projectRoot } from './common';

const option = (name: string, fallback: string) => {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 ? process.argv[i + 1] : fallback;
};

const PATCHES: [string, string][] = [
  ['bool bvhIntersect(', 'int bvhSteps[2] = int[2](0, 0);\nint bvhCalls[2] = int[2](0, 0);\nbool bvhIntersect('],
  ['  vec3 invDir = (vec3(greaterThanEqual(dir, vec3(0.0)))', '  bvhCalls[anyHit ? 1 : 0]++;\n  vec3 invDir = (vec3(greaterThanEqual(dir, vec3(0.0)))'],
  ['  do {\n', '  do {\n    bvhSteps[anyHit ? 1 : 0]++;\n'],
  ['  outSum = sum;', '  outSum = texelFetch(uAccumulation, pixel, 0) + vec4(float(bvhSteps[0]), float(bvhSteps[1]), float(bvhCalls[0]), float(bvhCalls[1]));'],
];

const sceneName = option('scene', 'bunny');
const [width, height] = option('size', '512x384').split('x').map(Number);
const spp = Number(option('spp', '4'));
const sceneFile = fileURLToPath(new URL(`test/fixtures/scenes/${sceneName}.json`, projectRoot()));
const scene = parseSceneText(readFileSync(sceneFile, 'utf8'));
const { files } = await readSceneFiles(scene, sceneFile);

const session = await openRenderSession();
try {
  const page = session.page;
  await page.addInitScript(() => {
    const original = WebGL2RenderingContext.prototype.shaderSource;
    WebGL2RenderingContext.prototype.shaderSource = function (shader: WebGLShader, text: string) {
      const w = window as unknown as { __traceSource?: string; __pageTraceSource?: string };
      const isTrace = text.includes('uSamplesPerDraw') && text.includes('outSum');
      if (isTrace) w.__pageTraceSource = text;
      return original.call(this, shader, isTrace && w.__traceSource ? w.__traceSource : text);
    };
  });
  await page.reload();
  await page.waitForFunction(() => document.body.dataset.ready === 'true');
  await session.load(scene, { width: 16, height: 16, seed: 1 } as LoadOptions, files);
  let text = await page.evaluate(() => (window as unknown as { __pageTraceSource?: string }).__pageTraceSource ?? '');
  for (const [search, replacement] of PATCHES) {
    if (!text.includes(search)) throw new Error(`pattern not found: ${search}`);
    text = text.replace(search, replacement);
  }
  await page.evaluate((t) => ((window as unknown as { __traceSource?: string }).__traceSource = t), text);
  await session.load(scene, { width, height, seed: 1 } as LoadOptions, files);
  await session.render(spp);
  const counts = await session.readLinear();
  const names = ['closest steps', 'any-hit steps', 'closest calls', 'any-hit calls'];
  const mean = (c: number) => {
    let sum = 0;
    for (let i = 0; i < width * height; i++) sum += counts[i * 4 + c];
    return sum / (width * height);
  };
  const quadMax = (c: number) => {
    let sum = 0;
    for (let y = 0; y < height; y += 2) {
      for (let x = 0; x < width; x += 2) {
        const at = (dx: number, dy: number) => counts[((y + dy) * width + x + dx) * 4 + c];
        sum += Math.max(at(0, 0), at(1, 0), at(0, 1), at(1, 1));
      }
    }
    return sum / ((width * height) / 4);
  };
  console.log(`${sceneName} ${width}x${height}, ${spp} spp, per pixel and sample:`);
  names.forEach((name, c) => console.log(`  ${name}: ${mean(c).toFixed(2)} (per quad, its busiest lane: ${quadMax(c).toFixed(2)})`));
  console.log(`  steps per call: closest ${(mean(0) / mean(2)).toFixed(2)}, any-hit ${(mean(1) / mean(3)).toFixed(2)}`);
} finally {
  await session.close();
}
