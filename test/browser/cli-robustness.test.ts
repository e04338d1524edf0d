/**
 * The built command line as a real process, on bad input and failures that
 * test/browser/cli.test.ts does not cover: every failure exits non-zero with
 * one line per problem (which file, which field, what to do) and no stack
 * trace, and an existing output file is replaced only by a complete new image
 * (never truncated, never left beside a temp file).
 * Needs `npm run build` (dist/cli and dist/web) and Chromium.
 */
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { type CliResult, ROOT, runPathtrace } from '../support/cli';

const SEED_SCENE = join(ROOT, 'test/fixtures/scenes/seed.json');
const TIMEOUT = 60_000;

type Result = CliResult;

function pathtrace(args: string[], env: NodeJS.ProcessEnv = {}, interruptAfterMs?: number): Promise<Result> {
  return runPathtrace(args, { cwd: dir, env: { PATHTRACE_DEBUG: '', ...env }, interruptAfterMs });
}

/** One line on stderr, no stack frames, nothing on stdout. */
function expectOneLine(result: Result, code: number, pattern: RegExp): void {
  expect(result.code, result.stderr).toBe(code);
  expect(result.stdout).toBe('');
  const lines = result.stderr.split('\n').filter((line) => line !== '');
  expect(lines, result.stderr).toHaveLength(1);
  expect(lines[0]).toMatch(pattern);
  expect(result.stderr).not.toMatch(/^\s+at |\.ts:\d+|\.js:\d+|Error:/m);
}

/** The files in `where` other than `keep`: temp files must never be left behind. */
function strays(where: string, keep: string[]): string[] {
  return readdirSync(where).filter((name) => !keep.includes(name));
}

/** A fresh, empty output directory. */
const outDir = () => mkdtempSync(join(dir, 'out-'));

let dir: string;
const OLD = Buffer.from('an existing output that must survive a failed render');

beforeAll(() => {
  expect(existsSync(join(ROOT, 'dist/cli/main.js')), 'dist/cli/main.js is missing: run `npm run build` first').toBe(true);
  expect(existsSync(join(ROOT, 'dist/web/headless.html')), 'dist/web is missing: run `npm run build` first').toBe(true);
  dir = mkdtempSync(join(tmpdir(), 'pathtrace-cli-robust-'));
});
afterAll(() => {
  if (dir) rmSync(dir, { recursive: true, force: true });
});

describe('bad input: exit 2, one line naming the file and the field', () => {
  it('a missing scene file', async () => {
    const missing = join(dir, 'nope.json');
    expectOneLine(await pathtrace(['render', missing]), 2, new RegExp(`^${missing}: cannot read scene: no such file`));
    expectOneLine(await pathtrace(['validate', missing]), 2, /nope\.json: cannot read scene/);
  }, TIMEOUT);

  it('unreadable JSON, with the line and column', async () => {
    const file = join(dir, 'broken.json');
    writeFileSync(file, '{\n  "camera": { "position": [0, 1, 5], "target": [0, 0, 0] },\n  "spheres": [ { "center": [0,0,0] "radius": 1 } ]\n}\n');
    expectOneLine(await pathtrace(['render', file]), 2, /^.*broken\.json: invalid JSON: .*line 3/);
  }, TIMEOUT);

  it('an invalid scene: the field and what is wrong, one line per problem', async () => {
    const file = join(dir, 'invalid.json');
    writeFileSync(file, JSON.stringify({ camera: { position: [0, 1, 5], target: [0, 1, 5] }, render: { maxBounces: 65 } }));
    const result = await pathtrace(['render', file]);
    expect(result.code).toBe(2);
    expect(result.stderr.trim().split('\n').sort()).toEqual([
      'camera.target: must differ from camera.position',
      'render.maxBounces: must be <= 64',
    ].sort().map((line) => expect.stringContaining(line)));
    expect(result.stderr).not.toMatch(/^\s+at /m);
  }, TIMEOUT);

  it('a bad mesh and a bad map: one line each naming the field, exit 2, no output, no Chromium left', async () => {
    const where = outDir();
    writeFileSync(join(where, 'garbage.ply'), 'ply\nthis is not a mesh\n');
    writeFileSync(join(where, 'bad.exr'), 'not an EXR');
    const scene = {
      version: 2,
      camera: { position: [0, 1, 4], target: [0, 0.5, 0] },
      image: { width: 16, height: 12 },
      environment: { map: 'bad.exr' },
      meshes: [{ file: 'garbage.ply' }, { file: 'missing.obj' }],
    };
    writeFileSync(join(where, 'scene.json'), JSON.stringify(scene));
    for (const command of ['render', 'validate']) {
      const result = await pathtrace([command, join(where, 'scene.json'), ...(command === 'render' ? ['-o', join(where, 'x.png')] : [])]);
      expect(result.code, result.stderr).toBe(2);
      const lines = result.stderr.split('\n').filter((line) => line !== '');
      expect(lines.map((line) => line.split(':')[0]).sort(), result.stderr).toEqual(['environment.map', 'meshes[0].file', 'meshes[1].file']);
      expect(result.stderr).not.toMatch(/^\s+at |Error:/m);
    }
    expect(strays(where, ['garbage.ply', 'bad.exr', 'scene.json'])).toEqual([]);
  }, TIMEOUT);

  it('a scene over 1 MB, and a scene that is not an object', async () => {
    const big = join(dir, 'big.json');
    writeFileSync(big, `{"camera":{"position":[0,1,5],"target":[0,0,0]}}${' '.repeat(1_000_001)}`);
    expectOneLine(await pathtrace(['render', big]), 2, /big\.json: .*larger than the limit of 1000000/);
    const array = join(dir, 'array.json');
    writeFileSync(array, '[1, 2, 3]');
    expectOneLine(await pathtrace(['render', array]), 2, /array\.json: must be an object/);
  }, TIMEOUT);

  it.each([
    [['--spp', '0'], /^--spp: /],
    [['--spp', '1e99'], /^--spp: /],
    [['--width', '-4'], /^--width: /],
    [['--width', '100000'], /^--width: /],
    [['--seed', 'x'], /^--seed: /],
    [['--exposure', 'NaN'], /^--exposure: /],
    [['--tonemap', '<b>'], /^--tonemap: /],
    [['--time', '0'], /^--time: /],
    [['--bogus'], /unknown option '--bogus'/],
  ])('bad flag %j', async (flags, pattern) => {
    expectOneLine(await pathtrace(['render', SEED_SCENE, ...flags]), 2, pattern);
  }, TIMEOUT);

  it('an unwritable output path fails before rendering', async () => {
    const started = Date.now();
    const noDir = join(dir, 'no-such-dir', 'x.png');
    expectOneLine(await pathtrace(['render', SEED_SCENE, '-o', noDir]), 2, new RegExp(`^-o: cannot write ${noDir}: directory .*: no such file or directory`));
    expectOneLine(await pathtrace(['render', SEED_SCENE, '--hdr', dir]), 2, /^--hdr: cannot write .*: it is a directory/);
    const file = join(dir, 'plain');
    writeFileSync(file, '');
    expectOneLine(await pathtrace(['render', SEED_SCENE, '-o', join(file, 'x.png')]), 2, /^-o: cannot write .*is not a directory/);
    // Well under the time Chromium alone takes to start.
    expect(Date.now() - started).toBeLessThan(15_000);
    rmSync(file);
  }, TIMEOUT);
});

describe('failures keep an existing output', () => {
  it('Chromium missing (PATHTRACE_CHROMIUM=/nonexistent): exit 1, what to do, outputs untouched', async () => {
    const out = outDir();
    const png = join(out, 'keep.png');
    writeFileSync(png, OLD);
    const result = await pathtrace(['render', SEED_SCENE, '-o', png, '--hdr', join(out, 'keep.pfm')], { PATHTRACE_CHROMIUM: '/nonexistent' });
    expectOneLine(result, 1, /Chromium not found at \/nonexistent: install it with "apt-get install chromium" or set PATHTRACE_CHROMIUM/);
    expect(readFileSync(png).equals(OLD)).toBe(true);
    expect(strays(out, ['keep.png'])).toEqual([]);
  }, TIMEOUT);

  it('a write that fails after rendering (the PFM cannot be created) replaces neither file', async () => {
    const out = outDir();
    const png = join(out, 'group.png');
    writeFileSync(png, OLD);
    // /proc passes the up-front checks for root but refuses to create files.
    const hdr = '/proc/pathtrace-robustness.pfm';
    const result = await pathtrace(['render', SEED_SCENE, '--width', '8', '--height', '6', '--spp', '1', '-o', png, '--hdr', hdr]);
    expect(result.code, result.stderr).not.toBe(0);
    const lines = result.stderr.split('\n').filter((line) => line !== '');
    expect(lines).toHaveLength(1);
    expect(lines[0]).toMatch(/cannot write \/proc\/pathtrace-robustness\.pfm: /);
    expect(readFileSync(png).equals(OLD), 'the PNG must not be replaced when its group fails').toBe(true);
    expect(strays(out, ['group.png'])).toEqual([]);
  }, TIMEOUT);

  // Ctrl-C: the CLI handles the signal itself (Playwright's handlers are
  // off), closes Chromium, prints one line and exits 130, whether the signal
  // comes during the render or while Chromium is still starting (made slow
  // here by a wrapper that sleeps before starting the real Chromium).
  const slowChromium = () => {
    const wrapper = join(outDir(), 'slow-chromium.sh');
    writeFileSync(wrapper, `#!/bin/sh\nsleep 4\nexec /usr/bin/chromium "$@"\n`, { mode: 0o755 });
    return { PATHTRACE_CHROMIUM: wrapper };
  };
  for (const [when, afterMs, env] of [['during a render', 6000, () => ({})], ['while Chromium starts', 2000, slowChromium]] as const) {
    it(`Ctrl-C ${when}: exit 130, one line, the old output intact, no temp file`, async () => {
      const out = outDir();
      const png = join(out, 'interrupted.png');
      writeFileSync(png, OLD);
      const args = ['render', SEED_SCENE, '--width', '64', '--height', '48', '--spp', '200000', '-o', png];
      const result = await pathtrace(args, env(), afterMs);
      expect(result.code, result.stderr).toBe(130);
      expect(result.stdout).toBe('');
      expect(result.stderr).toBe('interrupted\n');
      expect(readFileSync(png).equals(OLD)).toBe(true);
      expect(strays(out, ['interrupted.png'])).toEqual([]);
    }, TIMEOUT);
  }

  it('a successful render replaces the old file with a complete PNG', async () => {
    const out = outDir();
    const png = join(out, 'replaced.png');
    writeFileSync(png, OLD);
    const result = await pathtrace(['render', SEED_SCENE, '--width', '8', '--height', '6', '--spp', '2', '-o', png]);
    expect(result.code, result.stderr).toBe(0);
    const bytes = readFileSync(png);
    expect(bytes.subarray(0, 8).equals(Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]))).toBe(true);
    expect(bytes.subarray(-8, -4).toString('latin1')).toBe('IEND');
    expect(strays(out, ['replaced.png'])).toEqual([]);
  }, TIMEOUT);

  it('leaves no Chromium behind: no profile or temp directory, no process', async () => {
    // Chromium's profile goes to TMPDIR: a fresh one shows whatever is left.
    const temp = outDir();
    // A scene with a bad file: Chromium's start-up is stopped once the file is found bad.
    const badScene = join(outDir(), 'bad-mesh.json');
    writeFileSync(join(badScene, '..', 'bad.obj'), 'not a mesh\n');
    writeFileSync(badScene, JSON.stringify({ version: 2, camera: { position: [0, 1, 4], target: [0, 0, 0] }, meshes: [{ file: 'bad.obj' }] }));
    for (const [scene, code, ...args] of [[SEED_SCENE, 0, '--spp', '1'], [SEED_SCENE, 0, '--spp', '1', '--denoise'], [badScene, 2]] as const) {
      const result = await pathtrace(['render', scene, '--width', '8', '--height', '6', ...args, '-o', join(dir, 'left.png')], { TMPDIR: temp });
      expect(result.code, result.stderr).toBe(code);
      expect(readdirSync(temp), 'a Chromium profile was left behind').toEqual([]);
      const alive = execFileSync('ps', ['-eo', 'args'], { encoding: 'utf8' }).split('\n').filter((line) => line.includes(temp));
      expect(alive, 'a Chromium process survived').toEqual([]);
    }
  }, TIMEOUT);
});
