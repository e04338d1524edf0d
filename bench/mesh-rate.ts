/**
 * Meshes in the headless renderer (openRenderSession), for the report:
 *  - path rate (M paths/s) on the bunny scene (test/fixtures/scenes/bunny.json)
 *    and on generated scenes of ~80, ~3.7k, ~100k and ~1M triangles;
 *  - per load: wall time (decode + BVH build + upload + shader programs) and
 *    the shader work it caused (compileShader/linkProgram calls, their time,
 *    and a digest of every compiled source), to show that the shader does not
 *    depend on the triangle count (no per-mesh recompiles).
 *   npx tsx bench/mesh-rate.ts [--size 512x384] [--seconds 10] [--triangles 80,3700,100000,1000000]
 */
import { createHash } from 'node:crypto';
import { readFileSync } from 'node:fs';
import { openRenderSession, type RenderSession } from '../src/node/session';
import { assetReferences } from '../src/scene/assets';
import { parseSceneText } from '../src/scene/schema';
import type { Scene } from '../src/scene/types';
import { projectRoot, renderFor } from './common';
import { bumpySpherePly, meshScene } from './meshGen';

const option = (argv: string[], name: string, fallback: string) => {
  const i = argv.indexOf(`--${name}`);
  return i >= 0 && i + 1 < argv.length ? argv[i + 1] : fallback;
};

interface ShaderWork {
  compiles: number;
  links: number;
  ms: number;
  sources: string[];
}

/** Wraps the page's WebGL2 compile/link/status calls (SwiftShader may compile lazily at the status query). */
async function instrumentShaders(session: RenderSession): Promise<void> {
  // tsx (esbuild keepNames) wraps named functions in __name(): give the page one.
  await session.page.evaluate('globalThis.__name = (f) => f');
  await session.page.evaluate(() => {
    const work = { compiles: 0, links: 0, ms: 0, sources: [] as string[] };
    (window as unknown as { __shaderWork: typeof work }).__shaderWork = work;
    const proto = WebGL2RenderingContext.prototype as unknown as Record<string, (...a: unknown[]) => unknown>;
    const timed = (name: string, count?: (args: unknown[]) => void) => {
      const original = proto[name];
      proto[name] = function (this: WebGL2RenderingContext, ...args: unknown[]) {
        count?.(args);
        const start = performance.now();
        try {
          return original.apply(this, args);
        } finally {
          work.ms += performance.now() - start;
        }
      };
    };
    const sourceOf = new WeakMap<object, string>();
    const shaderSource = proto.shaderSource;
    proto.shaderSource = function (this: WebGL2RenderingContext, shader: unknown, source: unknown) {
      sourceOf.set(shader as object, source as string);
      return shaderSource.call(this, shader, source);
    };
    timed('compileShader', ([shader]) => {
      work.compiles++;
      work.sources.push(sourceOf.get(shader as object) ?? '');
    });
    timed('linkProgram', () => work.links++);
    timed('getProgramParameter');
    timed('getShaderParameter');
  });
}

async function takeShaderWork(session: RenderSession): Promise<ShaderWork> {
  return session.page.evaluate(() => {
    const w = (window as unknown as { __shaderWork: ShaderWork }).__shaderWork;
    const copy = { ...w, sources: [...w.sources] };
    Object.assign(w, { compiles: 0, links: 0, ms: 0, sources: [] });
    return copy;
  });
}

const digest = (sources: string[]) => sources.map((s) => createHash('sha256').update(s).digest('hex').slice(0, 8)).join(',');

async function measure(session: RenderSession, name: string, scene: Scene, files: Record<string, Uint8Array>, size: { width: number; height: number }, seconds: number) {
  await takeShaderWork(session);
  const t0 = performance.now();
  await session.load(scene, { ...size, seed: 1 }, files);
  await session.render(1);
  const loadMs = performance.now() - t0;
  const shaders = await takeShaderWork(session);
  const { spp, seconds: elapsed } = await renderFor(session, seconds, 1);
  const rate = (spp * size.width * size.height) / elapsed / 1e6;
  console.log(
    `${name}: ${rate.toFixed(3)} M paths/s (${spp} spp in ${elapsed.toFixed(1)} s at ${size.width}x${size.height}, ${scene.render.maxBounces} bounces); ` +
      `load+first sample ${loadMs.toFixed(0)} ms; shaders: ${shaders.compiles} compiles, ${shaders.links} links, ${shaders.ms.toFixed(0)} ms [${digest(shaders.sources)}]`,
  );
  return { name, rate, loadMs, shaders: { ...shaders, sources: digest(shaders.sources) } };
}

async function main(argv: string[]): Promise<void> {
  const [width, height] = option(argv, 'size', '512x384').split('x').map(Number);
  const seconds = Number(option(argv, 'seconds', '10'));
  const counts = option(argv, 'triangles', '80,3700,100000,1000000').split(',').map(Number);
  const size = { width, height };
  const session = await openRenderSession();
  try {
    await instrumentShaders(session);
    const bunnyUrl = new URL('test/fixtures/scenes/bunny.json', projectRoot());
    const bunny = parseSceneText(readFileSync(bunnyUrl, 'utf8'));
    const bunnyFiles = Object.fromEntries(assetReferences(bunny).map((r) => [r.file, new Uint8Array(readFileSync(new URL(r.file, bunnyUrl)))]));
    await measure(session, 'bunny.json', bunny, bunnyFiles, size, seconds);
    for (const n of counts) {
      const ply = bumpySpherePly(n);
      await measure(session, `generated ${n} triangles`, meshScene('sphere.ply', width, height), { 'sphere.ply': ply }, size, seconds);
    }
  } finally {
    await session.close();
  }
}

main(process.argv.slice(2)).catch((error) => {
  console.error(error);
  process.exit(1);
});
