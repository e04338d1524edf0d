/**
 * The GLSL texture lookup (src/shaders/textures/texture.glsl) against
 * Mitsuba 3.9.1's `bitmap` on the fixture of scripts/make-bitmap-lookups.py
 * (test/fixtures/bitmap-lookups: tiny.png, 5 x 3 RGBA8, and 154 lookups):
 * bilinear filtering between texel centres, repeat wrapping, the `uv`
 * transform and the sRGB decode before filtering. The image goes through
 * the renderer's own path (src/headless/textureKernels.ts: the PNG decoder,
 * TextureAtlas's plan and upload, packScene's TextureTable), placed in its
 * atlas pages beside a white decoy so that a lookup that strays out of its
 * rectangle shows.
 *
 * Tolerance, per value (the same bound as the TypeScript reference's test,
 * src/scene/texture/bitmapLookup.test.ts): both sides compute the texel
 * position `u' W - 0.5` in float32, Mitsuba after its float32 `to_uv`, the
 * shader after the record's float32 rows (`dot(uRow.xyz, (u, v, 1))`). Each
 * side rounds at most four times (products, sums, the scaling to texels),
 * each by at most 2^-24 of the magnitudes summed, so the positions differ by
 * at most 8 * 2^-24 * (sum of |terms| W + sum of |terms| H + 1) texels; a
 * bilinear value moves by at most that times the largest difference of
 * neighbouring texels (<= 1). The values: Mitsuba's sRGB decode is a
 * rational fit within 2.4e-6 relative of the exact curve, and the filter's
 * products and sums of non-negative terms are within a few ulps relative:
 * 1e-5 |value| covers them. The GPU's SRGB8_ALPHA8 fetch is not a float32
 * decode: SwiftShader returns multiples of 1/65280 (measured here over all
 * 256 bytes: at most 7.7e-6 from the exact curve, half a step), and the
 * bilinear weights sum to 1, so a decoded value carries up to DECODE_ERROR =
 * 8e-6 more (1/500 of an 8-bit step). So `|gpu - Mitsuba| <= 1e-5 |Mitsuba|
 * + 8 * 2^-24 * (M_u W + M_v H + 1)`, plus DECODE_ERROR for sRGB lookups.
 * The test also checks that it would catch a wrong lookup: the mutants of the
 * shader (no half-texel shift, clamp instead of repeat, a v flip) and of the
 * data (un-decoded sRGB, decoding after filtering, the rotation's sign)
 * differ from Mitsuba by more than 100 tolerances.
 */
import { readFileSync } from 'node:fs';
import { encode } from 'fast-png';
import { describe, expect, it } from 'vitest';
import type { TextureKernelRequest, TextureKernelResult } from '../../src/headless/textureKernels';
import type { RenderSession } from '../../src/node/session';
import { srgbToLinear } from '../../src/scene/color';
import type { Channel, Texture, UvTransform } from '../../src/scene/texture/texture';
import { useRenderSession } from '../support/browser';

interface Lookup {
  group: 'srgb' | 'raw' | 'channel' | 'transform';
  srgb: boolean;
  channel?: Channel;
  uv: [number, number];
  transform?: UvTransform;
  mitsuba: number[];
}

const DIR = new URL('../fixtures/bitmap-lookups/', import.meta.url);
const fixture = JSON.parse(readFileSync(new URL('lookups.json', DIR), 'utf8')) as {
  image: { file: string; width: number; height: number };
  lookups: Lookup[];
};
const W = fixture.image.width;
const H = fixture.image.height;
const TINY = 'tiny.png';
const DECOY = 'decoy.png';
const IDENTITY: UvTransform = { offset: [0, 0], scale: [1, 1], rotation: 0 };
/** The largest distance of the GPU's SRGB8_ALPHA8 decode from the exact curve (see the header). */
const DECODE_ERROR = 8e-6;
const TEXTURE_GLSL = readFileSync(new URL('../../src/shaders/textures/texture.glsl', import.meta.url), 'utf8');

/** A 3 x 4 opaque white image: taller than tiny.png, so the atlas puts it first and tiny.png beside it on its 8 x 8 page. */
const decoyPng = encode({ width: 3, height: 4, data: new Uint8Array(48).fill(255), channels: 4, depth: 8 });

type Input = 'color' | 'scalar';

/** The request of a set of lookups, and where each Mitsuba value is in its result (lookup index, component). */
interface Plan {
  request: TextureKernelRequest;
  /** Per fixture lookup, per Mitsuba value: [request lookup, component]. */
  values: [number, number][][];
}

/**
 * The kernel lookups of fixture lookups: a colour lookup for `srgb` and
 * `transform` (its RGB), a scalar of R, G and B for `raw` (RGB as stored),
 * the scalar of the channel for `channel` (Mitsuba read tiny-<c>.png, the
 * channel as its own grey image: the contract's baking). `rotationSign` -1
 * is the mutant with the rotation turned the other way.
 */
function plan(lookups: Lookup[], rotationSign = 1, shiftUv: [number, number] = [0, 0]): Plan {
  const textures: TextureKernelRequest['textures'] = [
    // The decoy in both 8-bit formats, so both atlas arrays hold it first.
    { texture: texture(DECOY, 'r', IDENTITY), input: 'color' },
    { texture: texture(DECOY, 'r', IDENTITY), input: 'scalar' },
  ];
  const known = new Map<string, number>();
  const textureIndex = (input: Input, channel: Channel, uv: UvTransform) => {
    const key = JSON.stringify([input, channel, uv]);
    if (!known.has(key)) known.set(key, textures.push({ texture: texture(TINY, channel, uv), input }) - 1);
    return known.get(key)!;
  };
  const requestLookups: TextureKernelRequest['lookups'] = [];
  const add = (t: number, uv: [number, number]) => requestLookups.push({ texture: t, uv: [uv[0] + shiftUv[0], uv[1] + shiftUv[1]] }) - 1;
  const values = lookups.map((l) => {
    const uv = l.transform ? { ...l.transform, rotation: rotationSign * l.transform.rotation } : IDENTITY;
    if (l.group === 'raw') return (['r', 'g', 'b'] as const).map((c): [number, number] => [add(textureIndex('scalar', c, uv), l.uv), 0]);
    if (l.group === 'channel') return [[add(textureIndex('scalar', l.channel!, uv), l.uv), 0] as [number, number]];
    const i = add(textureIndex('color', 'r', uv), l.uv);
    return [0, 1, 2].map((c): [number, number] => [i, c]);
  });
  const images = { [TINY]: readFileSync(new URL(TINY, DIR)).toString('base64'), [DECOY]: Buffer.from(decoyPng).toString('base64') };
  return { request: { images, textures, lookups: requestLookups }, values };
}

function texture(image: string, channel: Channel, uv: UvTransform): Texture {
  return { image, channel, scale: 1, uv: { offset: [...uv.offset], scale: [...uv.scale], rotation: uv.rotation } };
}

async function run(session: RenderSession, request: TextureKernelRequest): Promise<{ values: Float32Array; placements: TextureKernelResult['placements'] }> {
  const result = await session.page.evaluate((r) => window.pathtraceTextureKernels.run(r), request);
  const bytes = Buffer.from(result.values, 'base64');
  return { values: new Float32Array(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength)), placements: result.placements };
}

/** The GPU's values of each fixture lookup, in Mitsuba's channels. */
async function gpuValues(session: RenderSession, lookups: Lookup[], options: { textureSource?: string; rotationSign?: number; shiftUv?: [number, number] } = {}): Promise<number[][]> {
  const p = plan(lookups, options.rotationSign, options.shiftUv);
  const { values } = await run(session, { ...p.request, textureSource: options.textureSource });
  return p.values.map((parts) => parts.map(([i, c]) => values[i * 4 + c]));
}

/** The tolerance of one lookup's values (see the header). */
function tolerance(l: Lookup, m: number): number {
  const t = l.transform ?? IDENTITY;
  const r = (t.rotation * Math.PI) / 180;
  const [u, v] = l.uv;
  const mu = Math.abs(Math.cos(r) * t.scale[0] * u) + Math.abs(Math.sin(r) * t.scale[1] * v) + Math.abs(t.offset[0]);
  const mv = Math.abs(Math.sin(r) * t.scale[0] * u) + Math.abs(Math.cos(r) * t.scale[1] * v) + Math.abs(t.offset[1]);
  return 1e-5 * Math.abs(m) + 8 * 2 ** -24 * (mu * W + mv * H + 1) + (l.srgb ? DECODE_ERROR : 0);
}

/** The largest error over the lookups, in units of each value's tolerance. */
function worstError(lookups: Lookup[], values: number[][]): number {
  let worst = 0;
  lookups.forEach((l, i) => {
    expect(values[i]).toHaveLength(l.mitsuba.length);
    l.mitsuba.forEach((m, c) => {
      const error = Math.abs(values[i][c] - m) / tolerance(l, m);
      worst = Math.max(worst, Number.isNaN(error) ? Infinity : error);
    });
  });
  return worst;
}

const group = (name: Lookup['group']) => fixture.lookups.filter((l) => l.group === name);

/** texture.glsl with `from` replaced by `to` (once; the test fails if the text is not there). */
function mutant(from: string, to: string): string {
  expect(TEXTURE_GLSL, `texture.glsl no longer contains ${from}`).toContain(from);
  return TEXTURE_GLSL.replace(from, to);
}

describe('GLSL texture lookup against Mitsuba bitmap', () => {
  const session = useRenderSession();

  it('places tiny.png beside the decoy in both 8-bit atlas arrays', async () => {
    const p = plan(fixture.lookups);
    const { placements } = await run(session(), p.request);
    const byFormat = (image: string, format: string) => p.request.textures.flatMap((t, i) => (t.texture.image === image && placements[i].format === format ? [placements[i]] : []));
    for (const format of ['srgb8', 'linear8']) {
      const [decoy] = byFormat(DECOY, format);
      const tiny = byFormat(TINY, format);
      expect(decoy, format).toMatchObject({ x: 0, y: 0, width: 3, height: 4 });
      expect(tiny.length, format).toBeGreaterThan(0);
      for (const t of tiny) expect(t, format).toMatchObject({ layer: decoy.layer, x: 3, y: 0, width: W, height: H, halvings: 0 });
    }
  });

  it.each(['srgb', 'raw', 'channel', 'transform'] as const)('%s lookups equal Mitsuba within the float32 tolerance', async (name) => {
    const lookups = group(name);
    expect(lookups.length).toBeGreaterThanOrEqual(10);
    const worst = worstError(lookups, await gpuValues(session(), lookups));
    console.log(`texture lookup ${name}: worst error ${worst.toFixed(3)} tolerances`);
    expect(worst).toBeLessThanOrEqual(1);
  });

  it('would catch a wrong lookup: mutants of the shader and the data differ by more than 100 tolerances', async () => {
    const srgb = group('srgb');
    const farOff = (name: string, worst: number) => {
      console.log(`texture lookup mutant "${name}": worst error ${worst.toFixed(0)} tolerances`);
      expect(worst, name).toBeGreaterThan(100);
    };
    const shaderMutants: Record<string, string> = {
      'no half-texel shift': mutant('vec2 pos = st * size - 0.5;', 'vec2 pos = st * size;'),
      'clamp instead of repeat': mutant('ivec2 w = ivec2(i - size * floor(i / size));', 'ivec2 w = ivec2(i);'),
      'v flipped': mutant('vec2 pos = st * size - 0.5;', 'vec2 pos = vec2(st.x, 1.0 - st.y) * size - 0.5;'),
    };
    for (const [name, textureSource] of Object.entries(shaderMutants)) {
      farOff(name, worstError(srgb, await gpuValues(session(), srgb, { textureSource })));
    }
    // Half a texel off in the data instead (a uv convention off by half a texel).
    farOff('uv shifted half a texel', worstError(srgb, await gpuValues(session(), srgb, { shiftUv: [0.5 / W, 0.5 / H] })));
    // The same points read as stored (the atlas's RGBA8 instead of SRGB8_ALPHA8), and decoded after filtering.
    const raw = await gpuValues(session(), srgb.map((l) => ({ ...l, group: 'raw' as const })));
    farOff('sRGB not decoded', worstError(srgb, raw));
    farOff('sRGB decoded after filtering', worstError(srgb, raw.map((v) => v.map(srgbToLinear))));
    const transform = group('transform');
    farOff('rotation sign', worstError(transform, await gpuValues(session(), transform, { rotationSign: -1 })));
  });

  it('decodes every sRGB byte within DECODE_ERROR of the exact curve', async () => {
    const data = new Uint8Array(256 * 4).map((_, i) => (i % 4 === 3 ? 255 : i >> 2));
    const png = Buffer.from(encode({ width: 256, height: 1, data, channels: 4, depth: 8 })).toString('base64');
    const request: TextureKernelRequest = {
      images: { 'bytes.png': png },
      textures: [{ texture: texture('bytes.png', 'r', IDENTITY), input: 'color' }],
      lookups: Array.from({ length: 256 }, (_, i) => ({ texture: 0, uv: [(i + 0.5) / 256, 0.5] })),
    };
    const { values } = await run(session(), request);
    let worst = 0;
    for (let i = 0; i < 256; i++) {
      const exact = srgbToLinear(i / 255);
      for (let c = 0; c < 3; c++) worst = Math.max(worst, Math.abs(values[i * 4 + c] - exact));
    }
    console.log(`sRGB decode of the atlas: worst ${worst.toExponential(3)} from the exact curve`);
    expect(worst).toBeLessThanOrEqual(DECODE_ERROR);
  });

  it('keeps non-finite and huge coordinates finite', async () => {
    const uvs: [number, number][] = [[NaN, 0.5], [Infinity, -Infinity], [1e30, -1e30], [0.5, NaN]];
    const lookups = uvs.map((uv): Lookup => ({ group: 'srgb', srgb: true, uv, mitsuba: [0, 0, 0] }));
    for (const value of await gpuValues(session(), lookups)) expect(value.every(Number.isFinite), String(value)).toBe(true);
    const scalars = uvs.map((uv): Lookup => ({ group: 'channel', srgb: false, channel: 'a', uv, mitsuba: [0] }));
    for (const value of await gpuValues(session(), scalars)) expect(value.every(Number.isFinite), String(value)).toBe(true);
  });
});
