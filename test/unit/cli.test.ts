/**
 * The command line without a browser: a fake session module stands in for
 * headless Chromium, so these tests check arguments, scenes, output files,
 * exit codes and messages only.
 */
import { existsSync, mkdirSync, mkdtempSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterEach, beforeEach, describe, expect, it } from 'vitest';
import { run, type RunOptions } from '../../src/cli/main';
import { writeOutputs } from '../../src/cli/output';
import { decodePfm } from '../../src/image/pfm';
import { decodePng } from '../../src/cli/png';
import { formatDuration, formatRate } from '../../src/cli/progress';
import { renderBudget, type CliSession, type SessionModule } from '../../src/cli/render';
import type { LoadOptions, OutputsRequest } from '../../src/node/session';
import type { SceneAssets } from '../../src/scene/assets';
import type { Scene } from '../../src/scene/types';

const FIXTURES = new URL('../fixtures/scenes/', import.meta.url).pathname;
const fixture = (name: string) => join(FIXTURES, `${name}.json`);

class Capture {
  text = '';
  constructor(readonly isTTY = false) {}
  write(chunk: string): boolean {
    this.text += chunk;
    return true;
  }
  get lines(): string[] {
    return this.text.split('\n').filter((line) => line !== '');
  }
}

interface FakeOptions {
  openError?: Error;
  renderError?: Error;
  /** Virtual seconds each sample per pixel takes. */
  secondsPerSpp?: number;
  /** Give the session readOutputs (every image in one call, as the current page does). */
  readOutputs?: boolean;
}

/** A session module that "renders" a gradient that depends on the seed, on a virtual clock. */
function fakeSessionModule(options: FakeOptions = {}) {
  const log = {
    opened: 0,
    closed: 0,
    loads: [] as { scene: Scene; options: LoadOptions; files?: Record<string, Uint8Array>; assets?: SceneAssets }[],
    outputRequests: [] as OutputsRequest[],
    signals: [] as (AbortSignal | undefined)[],
    renders: [] as number[],
    displayed: [] as { exposure: number; toneMap: string }[],
    linearReads: 0,
    aovReads: 0,
  };
  let clock = 0;
  const now = () => clock;
  const module: SessionModule = {
    TONEMAPS: ['none', 'aces', 'agx', 'neutral'],
    async openRenderSession(sessionOptions) {
      log.opened++;
      log.signals.push(sessionOptions?.signal);
      if (options.openError) throw options.openError;
      let size: LoadOptions = { width: 0, height: 0, seed: 0 };
      let total = 0;
      const session: CliSession = {
        async load(scene, loadOptions, files, assets) {
          log.loads.push({ scene, options: loadOptions, files, assets });
          size = loadOptions;
          return { renderer: 'fake' };
        },
        async render(samples) {
          log.renders.push(samples);
          if (options.renderError) throw options.renderError;
          clock += samples * (options.secondsPerSpp ?? 0.01);
          total += samples;
          return total;
        },
        async readLinear() {
          log.linearReads++;
          const out = new Float32Array(size.width * size.height * 4);
          for (let i = 0; i < out.length; i++) out[i] = ((i + size.seed) % 7) / 4;
          return out;
        },
        async readDisplayed(display) {
          log.displayed.push(display);
          const out = new Uint8Array(size.width * size.height * 4);
          for (let i = 0; i < out.length; i++) out[i] = (i * 3 + size.seed) & 0xff;
          return out;
        },
        async readAovs() {
          log.aovReads++;
          const pixels = size.width * size.height;
          const albedo = new Float32Array(pixels * 4).fill(0.5);
          const normal = new Float32Array(pixels * 4);
          for (let i = 0; i < pixels; i++) normal[i * 4 + 1] = 1;
          return { albedo, normal, samples: 1 };
        },
        async close() {
          log.closed++;
        },
      };
      if (options.readOutputs) {
        session.readOutputs = async (request) => {
          log.outputRequests.push(request);
          const pixels = size.width * size.height;
          const displayed = new Uint8Array(pixels * 4).fill(request.denoise ? 7 : 9);
          const linear = request.linear ? new Float32Array(pixels * 4).fill(request.denoise ? 0.25 : 0.5) : undefined;
          const guides = request.aovs ? { albedo: new Float32Array(pixels * 4).fill(0.5), normal: new Float32Array(pixels * 4).fill(1) } : {};
          return { displayed, linear, ...guides };
        };
      }
      return session;
    },
  };
  return { module, log, now };
}

let dir: string;
beforeEach(() => {
  dir = mkdtempSync(join(tmpdir(), 'pathtrace-cli-'));
});
afterEach(() => {
  rmSync(dir, { recursive: true, force: true });
});

async function cli(argv: string[], extra: Partial<RunOptions> & { fake?: ReturnType<typeof fakeSessionModule> } = {}) {
  const stdout = new Capture();
  const stderr = new Capture(extra.stderr?.isTTY ?? false);
  const fake = extra.fake ?? fakeSessionModule();
  const code = await run(argv, {
    stdout,
    stderr,
    cwd: dir,
    env: {},
    now: fake.now,
    loadSession: async () => fake.module,
    ...extra,
    ...(extra.stderr ? { stderr } : {}),
  });
  return { code, stdout, stderr, log: fake.log };
}

/** No line of `text` looks like a stack frame. */
function expectNoStack(text: string): void {
  expect(text).not.toMatch(/^\s+at /m);
}

describe('arguments', () => {
  it.each([
    [['--spp', 'abc'], '--spp: must be a positive integer (got "abc")'],
    [['--spp', '0'], '--spp: must be a positive integer (got "0")'],
    [['--spp', '1.5'], '--spp: must be a positive integer (got "1.5")'],
    [['--spp', '1e3'], '--spp: must be a positive integer (got "1e3")'],
    [['--time', '0'], '--time: must be a positive number of seconds (got "0")'],
    [['--time', 'soon'], '--time: must be a positive number of seconds (got "soon")'],
    [['--spp', '4', '--time', '1'], '--spp, --time: give one of them, not both'],
    [['--seed', '-1'], '--seed: must be a non-negative integer (got "-1")'],
    [['--seed', '4294967296'], '--seed: must be at most 4294967295 (got "4294967296")'],
    [['--width', '0'], '--width: must be a positive integer (got "0")'],
    [['--height', '9000'], '--height: must be at most 8192 (got "9000")'],
    [['--exposure', 'bright'], '--exposure: must be a number of EV stops (got "bright")'],
    [['--exposure', 'Infinity'], '--exposure: must be a number of EV stops (got "Infinity")'],
    [['--tonemap', 'filmic'], '--tonemap: must be one of none, aces, agx, neutral (got "filmic")'],
  ])('render %j: exit 2 with one line', async (flags, line) => {
    const { code, stderr, stdout, log } = await cli(['render', fixture('seed'), ...flags]);
    expect(code).toBe(2);
    expect(stderr.lines).toEqual([line]);
    expect(stdout.text).toBe('');
    expect(log.opened).toBe(0);
  });

  it('accepts negative exposures and reports several bad flags at once', async () => {
    const ok = await cli(['render', fixture('furnace'), '--exposure', '-1.5', '--spp', '1']);
    expect(ok.code).toBe(0);
    expect(ok.log.displayed).toEqual([{ exposure: -1.5, toneMap: 'none' }]);
    const bad = await cli(['render', fixture('seed'), '--spp', 'x', '--seed', 'y', '--tonemap', 'z']);
    expect(bad.code).toBe(2);
    expect(bad.stderr.lines).toHaveLength(3);
  });

  it.each([
    [['render', fixture('seed'), '--bogus']],
    [['render']],
    [['render', fixture('seed'), 'extra']],
    [['frobnicate', fixture('seed')]],
    [['render', fixture('seed'), '--spp']],
  ])('%j: commander errors exit 2 with one line', async (argv) => {
    const { code, stderr } = await cli(argv);
    expect(code).toBe(2);
    expect(stderr.lines).toHaveLength(1);
    expect(stderr.lines[0]).toMatch(/^error: /);
  });

  it('no command prints help on stderr and exits 2', async () => {
    const { code, stderr, stdout } = await cli([]);
    expect(code).toBe(2);
    expect(stderr.text).toContain('Usage: pathtrace');
    expect(stdout.text).toBe('');
  });

  it('--help and --version exit 0 on stdout', async () => {
    const help = await cli(['render', '--help']);
    expect(help.code).toBe(0);
    expect(help.stdout.text).toContain('--spp <n>');
    expect(help.stdout.text).toContain('--hdr <file>');
    const version = await cli(['--version']);
    expect(version.code).toBe(0);
    expect(version.stdout.text).toMatch(/^\d+\.\d+\.\d+/);
  });
});

describe('validate', () => {
  it.each(['furnace', 'glossy', 'mirrors', 'seed', 'small-light'])('%s.json is valid: exit 0', async (name) => {
    const { code, stdout, stderr } = await cli(['validate', fixture(name)]);
    expect(code).toBe(0);
    expect(stdout.lines).toHaveLength(1);
    expect(stdout.text).toContain('valid scene');
    expect(stderr.text).toBe('');
  });

  it('an invalid scene: exit 2, one `path: message` line per problem', async () => {
    const scene = JSON.parse(readFileSync(fixture('seed'), 'utf8'));
    scene.spheres[2].material.roughness = 1.5;
    scene.spheres[0].radius = -1;
    scene.camera.fvo = 40;
    const file = join(dir, 'bad.json');
    writeFileSync(file, JSON.stringify(scene));
    const { code, stdout, stderr } = await cli(['validate', file]);
    expect(code).toBe(2);
    expect(stdout.text).toBe('');
    expect(stderr.lines).toHaveLength(3);
    for (const line of stderr.lines) expect(line).toMatch(/^[\w.[\]"]+: \S/);
    expect(stderr.text).toMatch(/^spheres\[2\]\.material\.roughness: /m);
    expect(stderr.text).toMatch(/^spheres\[0\]\.radius: /m);
    expect(stderr.text).toMatch(/^camera\.fvo: unknown key/m);
    expectNoStack(stderr.text);
  });

  it('a missing file: exit 2, names the file', async () => {
    const file = join(dir, 'nope.json');
    const { code, stderr } = await cli(['validate', file]);
    expect(code).toBe(2);
    expect(stderr.lines).toEqual([`${file}: cannot read scene: no such file`]);
  });

  it('a directory: exit 2', async () => {
    const { code, stderr } = await cli(['validate', dir]);
    expect(code).toBe(2);
    expect(stderr.lines).toEqual([`${dir}: cannot read scene: is a directory, not a scene file`]);
  });

  it('unreadable JSON: exit 2, one line naming the file', async () => {
    const file = join(dir, 'broken.json');
    writeFileSync(file, '{ "version": 1,\n  "camera": { ');
    const { code, stderr } = await cli(['validate', file]);
    expect(code).toBe(2);
    expect(stderr.lines).toHaveLength(1);
    expect(stderr.lines[0]).toMatch(new RegExp(`^${file.replace(/[.*+?^${}()|[\]\\]/g, '\\$&')}: invalid JSON`));
    expectNoStack(stderr.text);
  });

  it('a file over the size limit: exit 2 without reading it all', async () => {
    const file = join(dir, 'huge.json');
    writeFileSync(file, Buffer.alloc(2_000_000, 0x20));
    const { code, stderr } = await cli(['validate', file]);
    expect(code).toBe(2);
    expect(stderr.lines).toHaveLength(1);
    expect(stderr.lines[0]).toContain('limit');
  });

  it('render refuses an invalid scene before starting Chromium', async () => {
    const file = join(dir, 'bad.json');
    writeFileSync(file, '{"version": 2}');
    const { code, stderr, log } = await cli(['render', file]);
    expect(code).toBe(2);
    expect(stderr.lines.length).toBeGreaterThanOrEqual(1);
    expect(log.opened).toBe(0);
  });
});

describe('render with a fake session', () => {
  it('writes SCENE.png in the current directory by default, stdout stays clean', async () => {
    const { code, stdout, stderr, log } = await cli(['render', fixture('seed'), '--spp', '8']);
    expect(code).toBe(0);
    expect(stdout.text).toBe('');
    const png = decodePng(readFileSync(join(dir, 'seed.png')));
    expect([png.width, png.height]).toEqual([256, 192]);
    expect(log.loads[0].options).toEqual({ width: 256, height: 192, seed: 0 });
    expect(log.renders.reduce((a, b) => a + b, 0)).toBe(8);
    expect(log.displayed).toEqual([{ exposure: 0, toneMap: 'none' }]);
    expect(log.linearReads).toBe(0);
    expect(log.closed).toBe(1);
    // The only stderr output without a terminal is the summary line.
    expect(stderr.lines).toHaveLength(1);
    expect(stderr.lines[0]).toMatch(/^rendered 256x192 at 8 spp in [\d.]+ s \(.* paths\/s\) -> .*seed\.png$/);
  });

  it('--adaptive asks the page for adaptive sampling, and only then', async () => {
    const out = join(dir, 'adaptive.png');
    const { code, log } = await cli(['render', fixture('seed'), '-o', out, '--spp', '8', '--width', '32', '--height', '20', '--adaptive']);
    expect(code).toBe(0);
    expect(log.loads[0].options).toEqual({ width: 32, height: 20, seed: 0, adaptive: true });
    expect(log.renders.reduce((a, b) => a + b, 0)).toBe(8);
  });

  it('defaults to 256 spp, and passes seed, size, exposure and tonemap through', async () => {
    const out = join(dir, 'out.png');
    const hdr = join(dir, 'out.pfm');
    const args = ['render', fixture('seed'), '-o', out, '--hdr', hdr, '--seed', '7', '--width', '32', '--height', '20'];
    const { code, log, stderr } = await cli([...args, '--exposure', '1', '--tonemap', 'aces']);
    expect(code).toBe(0);
    expect(log.renders.reduce((a, b) => a + b, 0)).toBe(256);
    expect(log.loads[0].options).toEqual({ width: 32, height: 20, seed: 7 });
    expect(log.displayed).toEqual([{ exposure: 1, toneMap: 'aces' }]);
    const png = decodePng(readFileSync(out));
    expect([png.width, png.height]).toEqual([32, 20]);
    expect(png.rgba[0]).toBe(7);
    const pfm = decodePfm(readFileSync(hdr));
    expect([pfm.width, pfm.height]).toEqual([32, 20]);
    expect(pfm.rgb[0]).toBeCloseTo(((0 + 7) % 7) / 4);
    expect(pfm.rgb[1]).toBeCloseTo(((1 + 7) % 7) / 4);
    expect(stderr.lines.at(-1)).toContain(`${out}, ${hdr}`);
  });

  it('--width alone keeps the scene aspect', async () => {
    const { code, log } = await cli(['render', fixture('seed'), '--width', '64', '--spp', '1']);
    expect(code).toBe(0);
    expect(log.loads[0].options).toMatchObject({ width: 64, height: 48 });
  });

  it('--time renders chunks until the time is spent', async () => {
    const fake = fakeSessionModule({ secondsPerSpp: 0.01 });
    const { code, log, stderr } = await cli(['render', fixture('furnace'), '--time', '2'], { fake });
    expect(code).toBe(0);
    const total = log.renders.reduce((a, b) => a + b, 0);
    expect(total).toBeGreaterThanOrEqual(195);
    expect(total).toBeLessThanOrEqual(200);
    expect(Math.max(...log.renders)).toBeLessThanOrEqual(50);
    expect(stderr.text).toContain(`at ${total} spp`);
  });

  it('--time renders at least one sample even when one takes longer', async () => {
    const fake = fakeSessionModule({ secondsPerSpp: 5 });
    const { code, log } = await cli(['render', fixture('furnace'), '--time', '0.1'], { fake });
    expect(code).toBe(0);
    expect(log.renders).toEqual([1]);
  });

  it('draws a progress bar only when stderr is a terminal', async () => {
    const { code, stderr } = await cli(['render', fixture('furnace'), '--spp', '64'], { stderr: new Capture(true) });
    expect(code).toBe(0);
    expect(stderr.text).toContain('spp');
    expect(stderr.text).toContain('paths/s');
    expect(stderr.text).toMatch(/64\/64 spp|rendered 128x128 at 64 spp/);
  });
});

describe('files the scene names', () => {
  const meshScene = (mesh: string, map: string) =>
    JSON.stringify({
      version: 2,
      camera: { position: [0, 1, 4], target: [0, 0.5, 0], fov: 35 },
      image: { width: 16, height: 12 },
      environment: { map, intensity: 0.2 },
      meshes: [{ file: mesh, material: { color: [0.8, 0.8, 0.8] } }],
    });

  it('are decoded once, in Node: the session gets the decoded arrays, not the bytes', async () => {
    writeFileSync(join(dir, 'tri.obj'), 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n');
    writeFileSync(join(dir, 'mesh.json'), meshScene('tri.obj', new URL('../fixtures/envmaps/gradient-flat.hdr', import.meta.url).pathname));
    const { code, stderr, log } = await cli(['render', join(dir, 'mesh.json'), '--spp', '1']);
    expect(code, stderr.text).toBe(0);
    const [{ files, assets }] = log.loads;
    expect(Object.keys(files ?? {})).toEqual([]);
    expect(Array.from(assets!.meshes.get('tri.obj')!.indices)).toEqual([0, 1, 2]);
    expect(assets!.maps.size).toBe(1);
  });

  it('a bad mesh and a missing map: exit 2, one line each naming the field; a session opened meanwhile is closed', async () => {
    writeFileSync(join(dir, 'empty.obj'), 'v 0 0 0\n');
    writeFileSync(join(dir, 'bad.json'), meshScene('empty.obj', 'missing.exr'));
    const { code, stderr, log } = await cli(['render', join(dir, 'bad.json')]);
    expect(code).toBe(2);
    expect(stderr.lines).toHaveLength(2);
    expect(stderr.lines.some((line) => line.startsWith('environment.map: "missing.exr"'))).toBe(true);
    expect(stderr.lines.some((line) => line.startsWith('meshes[0].file: "empty.obj"'))).toBe(true);
    expect(log.loads).toEqual([]);
    expect(log.closed).toBe(log.opened);
    // Chromium's start-up is told to stop.
    expect(log.signals.map((signal) => signal?.aborted)).toEqual([true]);
  });

  it('a bad file is reported before a bad output path and before a session that cannot start', async () => {
    writeFileSync(join(dir, 'bad.json'), meshScene('missing.obj', 'missing.exr'));
    const badOutput = await cli(['render', join(dir, 'bad.json'), '-o', join(dir, 'no', 'such', 'dir.png')]);
    expect(badOutput.code).toBe(2);
    expect(badOutput.stderr.lines).toHaveLength(2);
    expect(badOutput.stderr.lines.every((line) => /^(environment\.map|meshes\[0\]\.file): /.test(line))).toBe(true);
    const noChromium = await cli(['render', join(dir, 'bad.json')], { fake: fakeSessionModule({ openError: new Error('no Chromium') }) });
    expect(noChromium.code).toBe(2);
    expect(noChromium.stderr.lines).toHaveLength(2);
  });
});

describe('output files', () => {
  it('a missing output directory fails fast with exit 2, before Chromium starts', async () => {
    const out = join(dir, 'no', 'such', 'dir', 'x.png');
    const { code, stderr, log } = await cli(['render', fixture('seed'), '-o', out]);
    expect(code).toBe(2);
    expect(log.opened).toBe(0);
    expect(stderr.lines).toHaveLength(1);
    expect(stderr.lines[0]).toMatch(/^-o: cannot write .*x\.png: directory .*: no such file or directory$/);
  });

  it('an output path inside a regular file, or that is a directory, fails with exit 2', async () => {
    const file = join(dir, 'file');
    writeFileSync(file, 'x');
    const inside = await cli(['render', fixture('seed'), '--hdr', join(file, 'x.pfm')]);
    expect(inside.code).toBe(2);
    expect(inside.stderr.lines[0]).toMatch(/^--hdr: cannot write .*is not a directory$/);
    mkdirSync(join(dir, 'out.png'));
    const isDir = await cli(['render', fixture('seed'), '-o', join(dir, 'out.png')]);
    expect(isDir.code).toBe(2);
    expect(isDir.stderr.lines).toEqual([`-o: cannot write ${join(dir, 'out.png')}: it is a directory`]);
    expect(inside.log.opened + isDir.log.opened).toBe(0);
  });

  it('refuses the same path for -o and --hdr', async () => {
    const out = join(dir, 'same');
    const { code, stderr } = await cli(['render', fixture('seed'), '-o', out, '--hdr', out]);
    expect(code).toBe(2);
    expect(stderr.lines[0]).toMatch(/^--hdr: /);
  });

  it('--aov writes the albedo and normal guides as PFM, once each, beside the PNG', async () => {
    const [albedo, normal] = [join(dir, 'albedo.pfm'), join(dir, 'normal.pfm')];
    const { code, stderr, log } = await cli(['render', fixture('seed'), '--spp', '2', '--width', '8', '--aov', `${albedo},${normal}`]);
    expect(code, stderr.text).toBe(0);
    expect(log.aovReads).toBe(1);
    const a = decodePfm(readFileSync(albedo));
    const n = decodePfm(readFileSync(normal));
    expect([a.width, n.width]).toEqual([8, 8]);
    expect(Array.from(a.rgb.slice(0, 3))).toEqual([0.5, 0.5, 0.5]);
    expect(Array.from(n.rgb.slice(0, 3))).toEqual([0, 1, 0]);
    expect(stderr.lines.at(-1)).toContain('albedo.pfm');
  });

  it('with readOutputs, --denoise --aov --hdr reads every image in one call (nothing else crosses)', async () => {
    const fake = fakeSessionModule({ readOutputs: true });
    const [hdr, albedo, normal] = [join(dir, 'x.pfm'), join(dir, 'albedo.pfm'), join(dir, 'normal.pfm')];
    const args = ['render', fixture('seed'), '--spp', '2', '--width', '8', '--denoise', '--hdr', hdr, '--aov', `${albedo},${normal}`, '--tonemap', 'aces'];
    const { code, stderr, log } = await cli(args, { fake });
    expect(code, stderr.text).toBe(0);
    expect(log.outputRequests).toEqual([{ width: 8, height: 6, display: { exposure: 0, toneMap: 'aces' }, linear: true, aovs: true, denoise: true }]);
    expect([log.linearReads, log.aovReads, log.displayed.length]).toEqual([0, 0, 0]);
    expect(decodePfm(readFileSync(hdr)).rgb[0]).toBe(0.25);
    expect(decodePfm(readFileSync(albedo)).rgb[0]).toBe(0.5);
    expect(decodePfm(readFileSync(normal)).rgb[0]).toBe(1);
    expect(decodePng(readFileSync(join(dir, 'seed.png'))).rgba[0]).toBe(7);
  });

  it('with readOutputs, a plain render asks for the linear image only with --hdr', async () => {
    const fake = fakeSessionModule({ readOutputs: true });
    const { code, log } = await cli(['render', fixture('seed'), '--spp', '1', '--width', '8'], { fake });
    expect(code).toBe(0);
    expect(log.outputRequests).toEqual([{ width: 8, height: 6, display: { exposure: 0, toneMap: 'none' }, linear: false, aovs: false, denoise: false }]);
  });

  it('--aov needs two different paths, none of them another output', async () => {
    const bad = ['one.pfm', 'a.pfm,', ',b.pfm', 'a.pfm,b.pfm,c.pfm', 'a.pfm,a.pfm'];
    for (const value of bad) {
      const { code, stderr, log } = await cli(['render', fixture('seed'), '--aov', value]);
      expect(code, value).toBe(2);
      expect(stderr.lines, value).toHaveLength(1);
      expect(stderr.lines[0], value).toMatch(/^--aov: /);
      expect(log.opened).toBe(0);
    }
    const out = join(dir, 'x.pfm');
    const clash = await cli(['render', fixture('seed'), '--hdr', out, '--aov', `${out},${join(dir, 'n.pfm')}`]);
    expect(clash.code).toBe(2);
    expect(clash.stderr.lines).toEqual([`--aov: ${out} is also the --hdr output; give them different names`]);
  });

  it('a render failure exits 1 with one line, keeps an existing output and leaves no temp file', async () => {
    const out = join(dir, 'keep.png');
    writeFileSync(out, 'old image');
    const error = new Error('page.evaluate: WebGL context lost\nCall log:\n  - waiting for something');
    const fake = fakeSessionModule({ renderError: error });
    const { code, stderr, log } = await cli(['render', fixture('seed'), '-o', out, '--hdr', join(dir, 'k.pfm')], { fake });
    expect(code).toBe(1);
    expect(stderr.lines).toEqual(['render failed: page.evaluate: WebGL context lost']);
    expect(readFileSync(out, 'utf8')).toBe('old image');
    expect(readdirSync(dir)).toEqual(['keep.png']);
    expect(log.closed).toBe(1);
  });

  it('replaces an existing output once the new image is complete', async () => {
    const out = join(dir, 'replace.png');
    writeFileSync(out, 'old image');
    const { code } = await cli(['render', fixture('furnace'), '-o', out, '--spp', '2']);
    expect(code).toBe(0);
    expect(decodePng(readFileSync(out)).width).toBe(128);
    expect(readdirSync(dir)).toEqual(['replace.png']);
  });
});

describe('rendering failures', () => {
  it('Chromium missing: exit 1 with its install hint on one line', async () => {
    const missing = Object.assign(new Error('Chromium not found at /usr/bin/chromium.\nInstall it: apt-get install chromium'), {
      name: 'ChromiumNotFoundError',
    });
    const fake = fakeSessionModule({ openError: missing });
    const { code, stderr } = await cli(['render', fixture('seed'), '--spp', '1'], { fake });
    expect(code).toBe(1);
    expect(stderr.lines).toEqual(['Chromium not found at /usr/bin/chromium. Install it: apt-get install chromium']);
    expect(existsSync(join(dir, 'seed.png'))).toBe(false);
  });

  it('a session module that cannot load: exit 1, one line', async () => {
    const { code, stderr } = await cli(['render', fixture('seed')], {
      loadSession: async () => {
        throw new Error('Cannot find module playwright-core');
      },
    });
    expect(code).toBe(1);
    expect(stderr.lines).toEqual(['error: cannot load the renderer: Cannot find module playwright-core']);
  });

  it('PATHTRACE_DEBUG=1 adds the stack trace', async () => {
    const fake = fakeSessionModule({ renderError: new Error('boom') });
    const quiet = await cli(['render', fixture('seed'), '--spp', '1'], { fake });
    expectNoStack(quiet.stderr.text);
    const loud = await cli(['render', fixture('seed'), '--spp', '1'], { fake, env: { PATHTRACE_DEBUG: '1' } });
    expect(loud.code).toBe(1);
    expect(loud.stderr.lines[0]).toBe('render failed: boom');
    expect(loud.stderr.text).toMatch(/^\s+at /m);
  });
});

describe('renderBudget', () => {
  function timed(secondsPerSpp: number) {
    let clock = 0;
    const calls: number[] = [];
    return {
      calls,
      now: () => clock,
      session: {
        async render(n: number) {
          calls.push(n);
          clock += n * secondsPerSpp;
          return calls.reduce((a, b) => a + b, 0);
        },
      },
    };
  }
  const quiet = { update() {} };

  it('renders exactly the asked samples, starting at 1 and growing towards half-second chunks', async () => {
    const t = timed(0.001);
    const result = await renderBudget(t.session, { kind: 'spp', spp: 1000 }, quiet, t.now);
    expect(result.spp).toBe(1000);
    expect(t.calls.reduce((a, b) => a + b, 0)).toBe(1000);
    expect(t.calls.slice(0, 4)).toEqual([1, 4, 16, 64]);
    expect(Math.max(...t.calls)).toBeLessThanOrEqual(500);
  });

  it('keeps slow renders at one sample per call', async () => {
    const t = timed(2);
    await renderBudget(t.session, { kind: 'spp', spp: 3 }, quiet, t.now);
    expect(t.calls).toEqual([1, 1, 1]);
  });
});

describe('export-mitsuba', () => {
  it('writes XML to stdout without -o', async () => {
    const { code, stdout } = await cli(['export-mitsuba', fixture('seed')]);
    expect(code).toBe(0);
    expect(stdout.text).toContain('<scene version="3.0.0"');
  });

  it('writes XML to -o, with --spp passed through', async () => {
    const out = join(dir, 'seed.xml');
    const { code, stdout } = await cli(['export-mitsuba', fixture('seed'), '-o', out, '--spp', '64']);
    expect(code).toBe(0);
    expect(stdout.text).toBe('');
    const xml = readFileSync(out, 'utf8');
    expect(xml).toContain('<scene version="3.0.0"');
    expect(xml).toMatch(/name="sample_count" value="64"/);
  });

  it('writes the baked textures beside -o, named after it, and refuses stdout for a textured scene', async () => {
    const piped = await cli(['export-mitsuba', fixture('textured')]);
    expect(piped.code).toBe(2);
    expect(piped.stdout.text).toBe('');
    expect(piped.stderr.lines).toEqual([`${fixture('textured')}: ground.material.baseColor is a texture, which the export bakes into image files beside the XML: pass -o OUT.xml`]);
    const out = join(dir, 'tex.xml');
    const { code } = await cli(['export-mitsuba', fixture('textured'), '-o', out]);
    expect(code).toBe(0);
    const written = readdirSync(dir).filter((f) => f.endsWith('.pfm')).sort();
    expect(written).toEqual(['tex-tex0-checker-rgb.pfm', 'tex-tex1-rough-g.pfm', 'tex-tex2-grid-rgb.pfm', 'tex-tex3-rough-b.pfm', 'tex-tex4-bumps-normal.pfm']);
    const xml = readFileSync(out, 'utf8');
    for (const file of written) expect(xml).toContain(`<string name="filename" value="${join(dir, file)}"/>`);
    expect(decodePfm(readFileSync(join(dir, 'tex-tex1-rough-g.pfm'))).width).toBe(128);
  });

  it('rejects a bad scene and a bad output path with exit 2', async () => {
    expect((await cli(['export-mitsuba', join(dir, 'missing.json')])).code).toBe(2);
    expect((await cli(['export-mitsuba', fixture('seed'), '-o', join(dir, 'x', 'y.xml')])).code).toBe(2);
    expect((await cli(['export-mitsuba', fixture('seed'), '--spp', '-3'])).code).toBe(2);
  });
});

describe('writeOutputs', () => {
  it('replaces no file when any of the group cannot be written', async () => {
    const first = join(dir, 'first.png');
    writeFileSync(first, 'old');
    const second = join(dir, 'gone', 'second.pfm');
    await expect(writeOutputs([
      { path: first, data: Buffer.from('new') },
      { path: second, data: Buffer.from('new') },
    ])).rejects.toMatchObject({ exitCode: 1, lines: [`cannot write ${second}: no such file or directory`] });
    expect(readFileSync(first, 'utf8')).toBe('old');
    expect(readdirSync(dir)).toEqual(['first.png']);
  });
});

describe('progress formatting', () => {
  it('formats rates and durations', () => {
    expect(formatRate(1_234_567)).toBe('1.23 M');
    expect(formatRate(950)).toBe('950');
    expect(formatRate(45_600)).toBe('45.6 k');
    expect(formatDuration(4.25)).toBe('4.3 s');
    expect(formatDuration(185)).toBe('3m 05s');
    expect(formatDuration(3720)).toBe('1h 02m');
    expect(formatDuration(NaN)).toBe('-');
  });
});
