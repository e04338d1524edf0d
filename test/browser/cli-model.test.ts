/**
 * `pathtrace render MODEL` end to end (the built CLI, headless Chromium): a
 * glTF model renders with no scene file, fitted on the ground and lit by the
 * bundled studio map, to a non-blank PNG; the scene `pathtrace scene MODEL`
 * prints renders to the same bits (the PFMs are byte for byte equal).
 * Needs `npm run build` first. Small and few samples: each run starts
 * Chromium and compiles the shaders. The round trip uses a small untextured
 * glTF: bench.glb's textured, normal-mapped program compiles for a minute
 * or more on SwiftShader, and the printed scene does not depend on the
 * model's materials (it names the file, without `material`).
 */
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { ROOT, runPathtrace } from '../support/cli';
import { decodePng } from '../../src/cli/png';
import { decodePfm } from '../../src/image/pfm';

const MODEL = join(ROOT, 'test/fixtures/meshes/bench.glb');
const SMALL_MODEL = join(ROOT, 'test/fixtures/meshes/ico-smooth.glb');
const OPTIONS = ['--width', '96', '--height', '60', '--spp', '4', '--seed', '11'];

let dir: string;
beforeAll(() => {
  expect(existsSync(join(ROOT, 'dist/cli/main.js')), 'dist/cli/main.js is missing: run `npm run build` first').toBe(true);
  dir = mkdtempSync(join(tmpdir(), 'pathtrace-cli-model-'));
});
afterAll(() => {
  if (dir) rmSync(dir, { recursive: true, force: true });
});

describe('pathtrace render MODEL (built CLI, headless Chromium)', () => {
  it(
    'renders bench.glb with no scene file; the printed scene of a model renders the same bits',
    async () => {
      const direct = await runPathtrace(['render', MODEL, ...OPTIONS, '-o', join(dir, 'direct.png'), '--hdr', join(dir, 'direct.pfm')]);
      expect(direct.stderr.trim().split('\n').at(-1)).toMatch(/^rendered 96x60 at 4 spp in /);
      expect(direct.code).toBe(0);

      // Not blank: the lit model and ground against the map's dark backdrop.
      const png = decodePng(readFileSync(join(dir, 'direct.png')));
      expect([png.width, png.height]).toEqual([96, 60]);
      const luma = Array.from({ length: 96 * 60 }, (_, p) => png.rgba[p * 4] + png.rgba[p * 4 + 1] + png.rgba[p * 4 + 2]);
      expect(Math.max(...luma) - Math.min(...luma)).toBeGreaterThan(150);
      const hdr = decodePfm(readFileSync(join(dir, 'direct.pfm')));
      expect(hdr.rgb.every(Number.isFinite)).toBe(true);

      // The scene as `pathtrace scene` prints it, saved where it was printed (its paths are relative to there).
      const small = await runPathtrace(['render', SMALL_MODEL, ...OPTIONS, '-o', join(dir, 'direct.png'), '--hdr', join(dir, 'direct.pfm')]);
      expect(small.code, small.stderr).toBe(0);
      const printed = await runPathtrace(['scene', SMALL_MODEL, '--width', '96', '--height', '60'], { cwd: dir });
      expect(printed.stderr).toBe('');
      expect(printed.code).toBe(0);
      writeFileSync(join(dir, 'model-scene.json'), printed.stdout);
      const json = JSON.parse(printed.stdout);
      expect(json.meshes[0]).not.toHaveProperty('material');

      const fromFile = await runPathtrace(['render', join(dir, 'model-scene.json'), ...OPTIONS, '-o', join(dir, 'file.png'), '--hdr', join(dir, 'file.pfm')]);
      expect(fromFile.code, fromFile.stderr).toBe(0);
      expect(readFileSync(join(dir, 'file.pfm')).equals(readFileSync(join(dir, 'direct.pfm')))).toBe(true);
      expect(readFileSync(join(dir, 'file.png')).equals(readFileSync(join(dir, 'direct.png')))).toBe(true);
    },
    240_000,
  );
});
