/**
 * The built command line, end to end: `node bin/pathtrace.js ...` as a child
 * process, rendering through headless Chromium. Needs `npm run build` (the
 * test script runs it first) and Chromium at /usr/bin/chromium (or
 * PATHTRACE_CHROMIUM).
 */
import { existsSync, mkdtempSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { type CliResult, ROOT, runPathtrace } from '../support/cli';
import { decodePfm } from '../../src/image/pfm';
import { decodePng } from '../../src/cli/png';

const scene = (name: string) => join(ROOT, 'test/fixtures/scenes', `${name}.json`);
const TIMEOUT = 120_000;

type Result = CliResult;

function pathtrace(args: string[], env: NodeJS.ProcessEnv = {}, cwd = ROOT): Promise<Result> {
  return runPathtrace(args, { env, cwd });
}

/** The exact sRGB encoding of a linear value clamped to [0, 1], as an 8-bit code. */
function srgb8(linear: number): number {
  const c = Math.min(1, Math.max(0, linear));
  const encoded = c <= 0.0031308 ? 12.92 * c : 1.055 * Math.pow(c, 1 / 2.4) - 0.055;
  return Math.round(encoded * 255);
}

let dir: string;
beforeAll(() => {
  expect(existsSync(join(ROOT, 'dist/cli/main.js')), 'dist/cli/main.js is missing: run `npm run build` first').toBe(true);
  expect(existsSync(join(ROOT, 'dist/web/headless.html')), 'dist/web is missing: run `npm run build` first').toBe(true);
  const chromium = process.env.PATHTRACE_CHROMIUM ?? '/usr/bin/chromium';
  expect(existsSync(chromium), `Chromium is missing at ${chromium}: apt-get install chromium`).toBe(true);
  dir = mkdtempSync(join(tmpdir(), 'pathtrace-cli-browser-'));
});
afterAll(() => {
  if (dir) rmSync(dir, { recursive: true, force: true });
});

describe('pathtrace render (built CLI, headless Chromium)', () => {
  const small = ['--width', '40', '--height', '30', '--spp', '4'];

  it(
    'writes a PNG and a PFM of the asked size; the PNG is the PFM, displayed',
    async () => {
      const png = join(dir, 'a.png');
      const pfm = join(dir, 'a.pfm');
      const result = await pathtrace(['render', scene('seed'), ...small, '--seed', '3', '-o', png, '--hdr', pfm]);
      expect(result.stderr.trim().split('\n').at(-1)).toMatch(/^rendered 40x30 at 4 spp in [\d.]+ s \(.* paths\/s\) -> /);
      expect(result.code).toBe(0);
      expect(result.stdout).toBe('');

      const image = decodePng(readFileSync(png));
      expect([image.width, image.height]).toEqual([40, 30]);
      const hdr = decodePfm(readFileSync(pfm));
      expect([hdr.width, hdr.height]).toEqual([40, 30]);
      expect(hdr.rgb.every(Number.isFinite)).toBe(true);

      // Not blank: the scene has bright sky, dark shadows and coloured spheres.
      let min = Infinity;
      let max = -Infinity;
      for (const v of hdr.rgb) [min, max] = [Math.min(min, v), Math.max(max, v)];
      expect(max - min).toBeGreaterThan(0.1);

      // With exposure 0 and no tone mapping the displayed pixel is the sRGB
      // encoding of the clamped mean radiance: this also checks that both
      // files have row 0 at the top once decoded (PFM stores rows bottom up).
      let worst = 0;
      for (let p = 0; p < 40 * 30; p++) {
        for (let c = 0; c < 3; c++) {
          worst = Math.max(worst, Math.abs(image.rgba[p * 4 + c] - srgb8(hdr.rgb[p * 3 + c])));
        }
        expect(image.rgba[p * 4 + 3]).toBe(255);
      }
      expect(worst).toBeLessThanOrEqual(1);
      // The bluish sky is at the top, the grey ground at the bottom.
      const blueness = (row: number) => {
        let sum = 0;
        for (let x = 0; x < 40; x++) sum += hdr.rgb[(row * 40 + x) * 3 + 2] - hdr.rgb[(row * 40 + x) * 3];
        return sum / 40;
      };
      expect(blueness(0)).toBeGreaterThan(0.05);
      expect(blueness(0)).toBeGreaterThan(blueness(29));
    },
    TIMEOUT,
  );

  it(
    'is deterministic: the same seed gives byte-identical files, another seed differs',
    async () => {
      const outputs = [] as { png: Buffer; pfm: Buffer }[];
      for (const [name, seed] of [['s1', '11'], ['s2', '11'], ['s3', '12']]) {
        const png = join(dir, `${name}.png`);
        const pfm = join(dir, `${name}.pfm`);
        const result = await pathtrace(['render', scene('seed'), ...small, '--seed', seed, '-o', png, '--hdr', pfm]);
        expect(result.code, result.stderr).toBe(0);
        outputs.push({ png: readFileSync(png), pfm: readFileSync(pfm) });
      }
      expect(outputs[0].png.equals(outputs[1].png)).toBe(true);
      expect(outputs[0].pfm.equals(outputs[1].pfm)).toBe(true);
      expect(outputs[0].pfm.equals(outputs[2].pfm)).toBe(false);
      expect(outputs[0].png.equals(outputs[2].png)).toBe(false);
    },
    TIMEOUT,
  );

  it(
    'writes SCENE.png in the current directory by default; --exposure brightens it',
    async () => {
      const cwd = mkdtempSync(join(dir, 'cwd-'));
      const dark = await pathtrace(['render', scene('small-light'), '--width', '32', '--height', '24', '--spp', '2'], {}, cwd);
      expect(dark.code, dark.stderr).toBe(0);
      expect(readdirSync(cwd)).toEqual(['small-light.png']);
      const darkImage = decodePng(readFileSync(join(cwd, 'small-light.png')));
      const bright = await pathtrace(
        ['render', scene('small-light'), '--width', '32', '--height', '24', '--spp', '2', '--exposure', '2', '-o', 'bright.png'],
        {},
        cwd,
      );
      expect(bright.code, bright.stderr).toBe(0);
      const brightImage = decodePng(readFileSync(join(cwd, 'bright.png')));
      const mean = (rgba: Uint8Array) => rgba.reduce((sum, v, i) => (i % 4 === 3 ? sum : sum + v), 0) / rgba.length;
      expect(mean(brightImage.rgba)).toBeGreaterThan(mean(darkImage.rgba));
    },
    TIMEOUT,
  );

  it(
    'renders for --time seconds, at least one sample; the furnace PFM is 1 everywhere',
    async () => {
      const pfm = join(dir, 'furnace.pfm');
      const result = await pathtrace(['render', scene('furnace'), '--width', '16', '--height', '16', '--time', '1', '-o', join(dir, 'f.png'), '--hdr', pfm]);
      expect(result.code, result.stderr).toBe(0);
      const spp = Number(/at (\d+) spp/.exec(result.stderr)?.[1]);
      expect(spp).toBeGreaterThanOrEqual(1);
      const image = decodePfm(readFileSync(pfm));
      for (const v of image.rgb) expect(Math.abs(v - 1)).toBeLessThan(1e-3);
    },
    TIMEOUT,
  );

  it(
    'fails with one line: exit 2 for a bad flag or scene, exit 1 without Chromium',
    async () => {
      const badFlag = await pathtrace(['render', scene('seed'), '--spp', 'lots']);
      expect(badFlag.code).toBe(2);
      expect(badFlag.stderr).toBe('--spp: must be a positive integer (got "lots")\n');

      const badScene = join(dir, 'bad.json');
      writeFileSync(badScene, JSON.stringify({ version: 1, camera: { position: [0, 0, 1], target: [0, 0, 0] }, spheres: [{ center: [0, 0, 0], radius: -1 }] }));
      const invalid = await pathtrace(['render', badScene]);
      expect(invalid.code).toBe(2);
      expect(invalid.stderr).toMatch(/^spheres\[0\]\.radius: .+\n$/);

      const noChromium = await pathtrace(['render', scene('seed'), '-o', join(dir, 'x.png')], { PATHTRACE_CHROMIUM: join(dir, 'no-chromium') });
      expect(noChromium.code).toBe(1);
      expect(noChromium.stderr.trim().split('\n')).toHaveLength(1);
      expect(noChromium.stderr).toContain('apt-get install chromium');
      expect(noChromium.stderr).not.toMatch(/^\s+at /m);
      expect(existsSync(join(dir, 'x.png'))).toBe(false);
    },
    TIMEOUT,
  );
});

describe('pathtrace validate and export-mitsuba (built CLI)', () => {
  it('validate: exit 0 for a fixture', async () => {
    const result = await pathtrace(['validate', scene('glossy')]);
    expect(result.code).toBe(0);
    expect(result.stdout).toContain('valid scene');
  });

  it('export-mitsuba writes XML to stdout and to -o', async () => {
    const piped = await pathtrace(['export-mitsuba', scene('seed')]);
    expect(piped.code).toBe(0);
    expect(piped.stdout).toMatch(/^<\?xml[^]*<scene version="3\.0\.0"[^]*<\/scene>\s*$/);
    const out = join(dir, 'seed.xml');
    const written = await pathtrace(['export-mitsuba', scene('seed'), '-o', out, '--spp', '32']);
    expect(written.code).toBe(0);
    expect(readFileSync(out, 'utf8')).toContain('<integer name="sample_count" value="32"/>');
  });
});
