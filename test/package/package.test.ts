/**
 * The npm package as users get it: `npm pack`, unpack into a consumer's
 * node_modules, then import it from Node and type-check a consumer against
 * its declarations. Needs `npm run build` first (the test script does it).
 */
import { execFileSync } from 'node:child_process';
import { cpSync, mkdirSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { beforeAll, describe, expect, it } from 'vitest';

const root = fileURLToPath(new URL('../../', import.meta.url));
const consumer = `${root}test-output/consumer/`;

describe('npm package', () => {
  beforeAll(() => {
    rmSync(consumer, { recursive: true, force: true });
    mkdirSync(`${consumer}unpacked`, { recursive: true });
    const packed = execFileSync('npm', ['pack', '--json', '--pack-destination', consumer], { cwd: root, encoding: 'utf8' });
    const tarball = JSON.parse(packed.slice(packed.indexOf('[')))[0].filename as string;
    execFileSync('tar', ['-xzf', `${consumer}${tarball}`, '-C', `${consumer}unpacked`]);
    // Dependencies (zod, gl-matrix) resolve from the project's node_modules above.
    mkdirSync(`${consumer}node_modules`, { recursive: true });
    cpSync(`${consumer}unpacked/package`, `${consumer}node_modules/pathtrace`, { recursive: true });
  });

  it('ships the library, its types, the CLI, the docs and the license', () => {
    const files = readdirSync(`${consumer}node_modules/pathtrace`, { recursive: true }).map(String);
    for (const f of ['dist/lib/pathtrace.js', 'dist/types/index.d.ts', 'bin/pathtrace.js', 'dist/cli/main.js', 'dist/web/headless.html', 'docs/scene-format.md', 'LICENSE', 'README.md']) {
      expect(files, f).toContain(f);
    }
  });

  it('imports PathTracer and parseScene from Node', () => {
    writeFileSync(
      `${consumer}use.mjs`,
      `import { PathTracer, parseScene, TONEMAPS } from 'pathtrace';
       const scene = parseScene({ camera: { position: [0, 1, 5], target: [0, 0, 0] }, spheres: [{ center: [0, 0, 0], radius: 1 }] });
       console.log(JSON.stringify({ tracer: typeof PathTracer, spheres: scene.spheres.length, tonemaps: TONEMAPS }));`,
    );
    const out = JSON.parse(execFileSync('node', ['use.mjs'], { cwd: consumer, encoding: 'utf8' }));
    expect(out).toEqual({ tracer: 'function', spheres: 1, tonemaps: ['none', 'aces', 'neutral', 'agx'] });
  });

  it('type-checks a consumer against the shipped declarations', () => {
    writeFileSync(
      `${consumer}use.ts`,
      `import { PathTracer, parseScene, type Scene } from 'pathtrace';
       const scene: Scene = parseScene({ camera: { position: [0, 1, 5], target: [0, 0, 0] } });
       export function start(canvas: HTMLCanvasElement): number {
         const tracer = new PathTracer(canvas, scene, { seed: 1 });
         tracer.render(4);
         tracer.display({ exposure: 0, toneMap: 'aces' });
         return tracer.sampleCount;
       }
       // @ts-expect-error roughness must be a number
       export const bad: Scene['spheres'][number] = { center: [0, 0, 0], radius: 1, material: { color: [1, 1, 1], roughness: 'x' } };`,
    );
    writeFileSync(
      `${consumer}tsconfig.json`,
      JSON.stringify({
        compilerOptions: { strict: true, noEmit: true, module: 'ESNext', moduleResolution: 'Bundler', target: 'ES2022', lib: ['ES2022', 'DOM'], skipLibCheck: false, types: [] },
        files: ['use.ts'],
      }),
    );
    execFileSync(`${root}node_modules/.bin/tsc`, ['-p', 'tsconfig.json'], { cwd: consumer, encoding: 'utf8' });
  });
});
