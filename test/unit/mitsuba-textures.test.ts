/**
 * The Mitsuba export of textures (src/scene/mitsubaTextures.ts and the
 * exporter): the adapters the contract names, the baked images' values
 * (what Mitsuba's `bitmap` must filter to give the format's lookup: the
 * reference lookup bitmapLookup.ts at each texel centre, times the scale),
 * the uv transforms (checked as matrices against the format's formula,
 * Mitsuba's rectangle coordinates included) and the integrator. No
 * Mitsuba here: the render of the export was compared with the reference by
 * hand (see the report of the branch `texexport`).
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { decodePfm } from '../../src/image/pfm';
import { readSceneFiles } from '../../src/node/sceneFiles';
import { srgbToLinear } from '../../src/scene/color';
import { bakedTextureFile, exportMitsuba, MITSUBA_GROUND_SIZE } from '../../src/scene/mitsuba';
import { bakeTexture, cutoutFactor, MitsubaTextureBaker, uvTransformElements } from '../../src/scene/mitsubaTextures';
import type { XmlNode } from '../../src/scene/mitsubaXml';
import { parseSceneText } from '../../src/scene/schema';
import { bitmapLookup, transformUv, type RgbaImage } from '../../src/scene/texture/bitmapLookup';
import type { TextureImage } from '../../src/scene/texture/image';
import type { Texture } from '../../src/scene/texture/texture';
import type { Scene } from '../../src/scene/types';

const SCENE_FILE = new URL('../fixtures/scenes/textured.json', import.meta.url).pathname;

let loaded: ReturnType<typeof loadTexturedExport> | undefined;
/** textured.json exported (once: decoding its map and images takes a second). */
const texturedExport = () => (loaded ??= loadTexturedExport());
async function loadTexturedExport() {
  const scene = parseSceneText(readFileSync(SCENE_FILE, 'utf8'));
  const { assets } = await readSceneFiles(scene, SCENE_FILE);
  const result = exportMitsuba(scene, {
    images: assets.images,
    meshPath: (i) => `mesh${i}.ply`,
    texturePath: (name) => `/out/${name}`,
  });
  return { scene, images: assets.images!, ...result };
}

/** A minimal XML reader for what serializeXml writes (one element per line). */
interface Node {
  tag: string;
  attrs: Record<string, string>;
  children: Node[];
}
function parseXml(xml: string): Node {
  const root: Node = { tag: '#root', attrs: {}, children: [] };
  const stack = [root];
  for (const line of xml.split('\n')) {
    const open = /^\s*<([a-z_]+)((?:\s+[a-z_]+="[^"]*")*)\s*(\/?)>\s*$/.exec(line);
    const close = /^\s*<\/([a-z_]+)>\s*$/.exec(line);
    if (open) {
      const attrs = Object.fromEntries([...open[2].matchAll(/([a-z_]+)="([^"]*)"/g)].map((m) => [m[1], m[2]]));
      const node: Node = { tag: open[1], attrs, children: [] };
      stack[stack.length - 1].children.push(node);
      if (open[3] !== '/') stack.push(node);
    } else if (close) {
      expect(stack.pop()!.tag).toBe(close[1]);
    }
  }
  expect(stack).toHaveLength(1);
  return root.children[0];
}
const childrenOf = (node: Node, tag: string) => node.children.filter((c) => c.tag === tag);
const only = (node: Node, tag: string) => {
  const found = childrenOf(node, tag);
  expect(found, `one <${tag}> in <${node.tag} ${JSON.stringify(node.attrs)}>`).toHaveLength(1);
  return found[0];
};
const named = (node: Node, name: string) => node.children.find((c) => c.attrs.name === name);

/** 3x3 row-major affine matrices, as Mitsuba composes the XML's transform elements (each left-multiplying). */
type M3 = number[];
const mul = (a: M3, b: M3): M3 => Array.from({ length: 9 }, (_, k) => [0, 1, 2].reduce((s, j) => s + a[Math.floor(k / 3) * 3 + j] * b[j * 3 + (k % 3)], 0));
function elementMatrix(e: { tag: string; attrs: Record<string, string> }): M3 {
  const x = Number(e.attrs.x ?? (e.tag === 'scale' ? 1 : 0));
  const y = Number(e.attrs.y ?? (e.tag === 'scale' ? 1 : 0));
  if (e.tag === 'scale') return [x, 0, 0, 0, y, 0, 0, 0, 1];
  if (e.tag === 'translate') return [1, 0, x, 0, 1, y, 0, 0, 1];
  expect(e.tag).toBe('rotate');
  expect(e.attrs.z).toBe('1');
  const a = (Number(e.attrs.angle) * Math.PI) / 180;
  // Mitsuba's rotate: counter-clockwise, [[cos, -sin], [sin, cos]] (transform.h).
  return [Math.cos(a), -Math.sin(a), 0, Math.sin(a), Math.cos(a), 0, 0, 0, 1];
}
const composed = (elements: { tag: string; attrs: Record<string, string> }[]) => elements.reduce((m, e) => mul(elementMatrix(e), m), [1, 0, 0, 0, 1, 0, 0, 0, 1]);
const apply = (m: M3, [u, v]: [number, number]): [number, number] => [m[0] * u + m[1] * v + m[2], m[3] * u + m[4] * v + m[5]];
const asNodes = (xml: XmlNode[]) => xml.map((e) => ({ tag: e.tag, attrs: Object.fromEntries(e.attrs) }));

const rgba8 = (image: TextureImage): RgbaImage => {
  expect(image.encoding).toBe('u8');
  return { width: image.width, height: image.height, data: image.data as Uint8Array };
};
const texelCentre = (image: { width: number; height: number }, t: number): [number, number] => [((t % image.width) + 0.5) / image.width, (Math.floor(t / image.width) + 0.5) / image.height];
const texture = (fields: Partial<Texture> = {}): Texture => ({ image: 'a.png', channel: 'r', scale: 1, uv: { offset: [0, 0], scale: [1, 1], rotation: 0 }, ...fields });
/** `actual` is `expected` stored as float32 (within its rounding). */
const expectFloat32 = (actual: number, expected: number) => expect(Math.abs(actual - expected)).toBeLessThanOrEqual(2 ** -23 * Math.abs(expected));
/** A small 8-bit image whose every channel takes many values (several in sRGB's linear segment). */
function testImage(width = 7, height = 5): TextureImage {
  const data = new Uint8Array(width * height * 4);
  for (let i = 0; i < data.length; i++) data[i] = (i * 37 + (i >> 2) * 11) % 256;
  return { width, height, format: 'png', encoding: 'u8', data };
}

describe('Mitsuba export of textured.json', () => {
  it('names the adapters as the contract says: textures in principled, normalmap inside twosided on meshes, path (nothing see-through)', async () => {
    const { xml } = await texturedExport();
    const scene = parseXml(xml);
    expect(only(scene, 'integrator').attrs.type).toBe('path');
    const shapes = childrenOf(scene, 'shape');
    expect(shapes.map((s) => s.attrs.type)).toEqual(['rectangle', 'ply', 'ply']);

    const ground = only(shapes[0], 'bsdf');
    expect(ground.attrs.type).toBe('principled');
    expect(childrenOf(ground, 'texture').map((t) => t.attrs.name)).toEqual(['base_color', 'roughness']);

    const box = only(shapes[1], 'bsdf');
    expect(box.attrs.type).toBe('twosided');
    const boxPrincipled = only(box, 'bsdf');
    expect(boxPrincipled.attrs.type).toBe('principled');
    expect(childrenOf(boxPrincipled, 'texture').map((t) => t.attrs.name)).toEqual(['base_color', 'metallic']);
    expect(named(boxPrincipled, 'roughness')).toMatchObject({ tag: 'float', attrs: { value: '0.35' } });

    const bumpy = only(shapes[2], 'bsdf');
    expect(bumpy.attrs.type).toBe('twosided');
    const normalmap = only(bumpy, 'bsdf');
    expect(normalmap.attrs.type).toBe('normalmap');
    expect(only(normalmap, 'texture').attrs.name).toBe('normalmap');
    expect(only(normalmap, 'bsdf').attrs.type).toBe('principled');
    expect(childrenOf(only(normalmap, 'bsdf'), 'texture')).toHaveLength(0);

    const bitmaps = [ground, boxPrincipled, normalmap].flatMap((b) => childrenOf(b, 'texture'));
    expect(bitmaps).toHaveLength(5);
    for (const t of bitmaps) {
      expect(t.attrs.type).toBe('bitmap');
      expect(named(t, 'filename')!.attrs.value).toMatch(/^\/out\/tex\d-[a-z]+-[a-z]+\.pfm$/);
      expect(named(t, 'raw')!.attrs.value).toBe('true');
      expect(named(t, 'filter_type')!.attrs.value).toBe('bilinear');
      expect(named(t, 'wrap_mode')!.attrs.value).toBe('repeat');
    }
    // Meshes' coordinates are the format's: no transform where the texture has none.
    expect(childrenOf(boxPrincipled, 'texture').every((t) => childrenOf(t, 'transform').length === 0)).toBe(true);
  });

  it("turns the ground rectangle's coordinates into the format's (x, z) and then applies the texture's uv", async () => {
    const { scene, xml } = await texturedExport();
    const groundBsdf = only(childrenOf(parseXml(xml), 'shape')[0], 'bsdf');
    const [cx, , cz] = scene.camera.position;
    const side = MITSUBA_GROUND_SIZE;
    const baseColor = scene.ground!.material as { baseColor: Texture; roughness: Texture };
    for (const [name, uv] of [['base_color', baseColor.baseColor.uv], ['roughness', baseColor.roughness.uv]] as const) {
      const transform = only(childrenOf(groundBsdf, 'texture').find((t) => t.attrs.name === name)!, 'transform');
      expect(transform.attrs.name).toBe('to_uv');
      const m = composed(transform.children);
      for (const [x, z] of [[0, 0], [1.3, -2.7], [-40, 25], [cx, cz]]) {
        // Mitsuba's rectangle (checked with Mitsuba 3.9.1): uv = ((x - cx) / side + 1/2, (cz - z) / side + 1/2).
        const mitsubaUv: [number, number] = [(x - cx) / side + 0.5, (cz - z) / side + 0.5];
        const [u, v] = apply(m, mitsubaUv);
        const [eu, ev] = transformUv([x, z], uv);
        expect(Math.abs(u - eu) + Math.abs(v - ev), `${name} at (${x}, ${z})`).toBeLessThan(1e-9);
      }
    }
  });

  it('bakes each use once: sRGB-decoded colour, split channels times their scale, the normal map as stored', async () => {
    const { textures, images } = await texturedExport();
    expect(textures.map((t) => t.name)).toEqual(['tex0-checker-rgb.pfm', 'tex1-rough-g.pfm', 'tex2-grid-rgb.pfm', 'tex3-rough-b.pfm', 'tex4-bumps-normal.pfm']);
    const uses: [string, number, 'srgb' | 'stored', number][] = [
      ['../textures/checker.png', 3, 'srgb', 1],
      ['../textures/rough.png', 1, 'stored', 0.8], // roughness: channel g, scale 0.8
      ['../textures/grid.png', 3, 'srgb', 1],
      ['../textures/rough.png', 1, 'stored', 1], // metallic: channel b
      ['../textures/bumps.png', 3, 'stored', 1],
    ];
    const channelOf = [0, 1, 0, 2, 0];
    textures.forEach((baked, k) => {
      const [file, channels, decode, scale] = uses[k];
      const image = rgba8(images.get(file)!);
      expect([baked.width, baked.height, baked.channels, baked.filter]).toEqual([image.width, image.height, channels, 'bilinear']);
      let worst = 0;
      for (let t = 0; t < image.width * image.height; t++) {
        const lookup = bitmapLookup(image, texelCentre(image, t), { srgb: decode === 'srgb' });
        for (let c = 0; c < channels; c++) {
          const expected = lookup[channels === 1 ? channelOf[k] : c] * scale;
          worst = Math.max(worst, Math.abs(baked.values[t * channels + c] - expected));
        }
      }
      // float32 storage of a value in [0, 1].
      expect(worst, baked.name).toBeLessThan(1e-7);
    });
    // And the file holds the same values (PFM rows from the bottom; decodePfm repeats a grey channel 3 times).
    const pfm = decodePfm(bakedTextureFile(textures[1]));
    expect(pfm.width).toBe(128);
    expect(Array.from(pfm.rgb.filter((_, i) => i % 3 === 0))).toEqual(Array.from(textures[1].values));
    expect(new TextDecoder().decode(bakedTextureFile(textures[1]).subarray(0, 3))).toBe('Pf\n');
    expect(new TextDecoder().decode(bakedTextureFile(textures[0]).subarray(0, 3))).toBe('PF\n');
  });
});

describe('bakeTexture', () => {
  it('decodes an 8-bit colour texel as srgbToLinear(x / 255) times the (colour) scale, alpha dropped', () => {
    const image = testImage();
    const scale: [number, number, number] = [0.5, 2, 1];
    const baked = bakeTexture(image, texture({ scale }), 'color');
    expect(baked.channels).toBe(3);
    for (let t = 0; t < image.width * image.height; t++) {
      for (let c = 0; c < 3; c++) expectFloat32(baked.values[t * 3 + c], srgbToLinear(image.data[t * 4 + c] / 255) * scale[c]);
    }
  });

  it('decodes 16-bit colour from sRGB too, and keeps float images linear; scalars read them as stored', () => {
    const u16: TextureImage = { width: 2, height: 1, format: 'png', encoding: 'u16', data: Uint16Array.from([0x8080, 1000, 65535, 7, 0, 40000, 123, 65535]) };
    const colour = bakeTexture(u16, texture(), 'color');
    expect(colour.values[0]).toBeCloseTo(srgbToLinear(0x8080 / 65535), 7);
    expect(colour.values[0]).toBeCloseTo(0.21582, 4); // Mitsuba's reading of 0x8080 (test/fixtures/bitmap-lookups/README.md)
    expect(colour.values[4]).toBeCloseTo(srgbToLinear(40000 / 65535), 7);
    expect(bakeTexture(u16, texture({ channel: 'a', scale: 0.5 }), 'scalar').values).toEqual(Float32Array.from([7 / 65535 / 2, 0.5]));
    const f32: TextureImage = { width: 1, height: 1, format: 'exr', encoding: 'f32', data: Float32Array.from([3.5, 0.25, 0.125, 1]) };
    expect(Array.from(bakeTexture(f32, texture({ scale: 2 }), 'color').values)).toEqual([7, 0.5, 0.25]);
  });

  it('splits a scalar channel as stored (no sRGB decoding) times the scale', () => {
    const image = testImage();
    for (const [channel, c] of [['r', 0], ['g', 1], ['b', 2], ['a', 3]] as const) {
      const baked = bakeTexture(image, texture({ channel, scale: 0.7 }), 'scalar');
      expect([baked.channels, baked.filter]).toEqual([1, 'bilinear']);
      baked.values.forEach((v, t) => expectFloat32(v, (image.data[t * 4 + c] / 255) * 0.7));
    }
  });

  it("re-encodes a normal map so that Mitsuba's normalize(2 rgb' - 1) is the format's normalize((2 rgb - 1) * (s, s, 1)), after filtering too", () => {
    const image = testImage();
    for (const scale of [1, 0.5, -2]) {
      const baked = bakeTexture(image, texture({ scale }), 'normal');
      const normalize = (v: number[]) => v.map((x) => x / Math.hypot(...v));
      // At points between texels: the bilinear filter of the baked values (its four texels, as Mitsuba weighs them).
      for (const uv of [[0.13, 0.77], [0.5, 0.5], [0.99, 0.02], [0.31, 0.4]] as [number, number][]) {
        const stored = bitmapLookup(rgba8(image), uv, { srgb: false });
        const expected = normalize([(2 * stored[0] - 1) * scale, (2 * stored[1] - 1) * scale, 2 * stored[2] - 1]);
        const bakedRgb = filterBaked(baked, uv);
        const mitsuba = normalize(bakedRgb.map((x) => 2 * x - 1));
        mitsuba.forEach((x, i) => expect(x, `scale ${scale} at ${uv}`).toBeCloseTo(expected[i], 6));
      }
    }
  });

  it('bakes a cut-out upsampled and thresholded, read nearest: 0 or the scale, the renderer’s value at each fine texel centre', () => {
    const image = testImage(6, 4);
    const k = cutoutFactor(6, 4);
    expect(k).toBe(4);
    const baked = bakeTexture(image, texture({ channel: 'g', scale: 0.9, cutoff: 0.5 }), 'scalar');
    expect([baked.width, baked.height, baked.channels, baked.filter]).toEqual([24, 16, 1, 'nearest']);
    let ones = 0;
    baked.values.forEach((v, t) => {
      const expected = bitmapLookup(rgba8(image), texelCentre(baked, t), { srgb: false })[1] >= 0.5 ? 0.9 : 0;
      expect(v).toBeCloseTo(expected, 7);
      if (v > 0) ones++;
    });
    expect(ones).toBeGreaterThan(20);
    expect(ones).toBeLessThan(baked.values.length - 20);
    // Large images are not upsampled beyond the limit.
    expect(cutoutFactor(4096, 4096)).toBe(1);
    expect(cutoutFactor(1024, 1024)).toBe(2);
  });
});

/** Mitsuba's bilinear filter (test/fixtures/bitmap-lookups/README.md) of a 3-channel baked image. */
function filterBaked(baked: { width: number; height: number; values: Float32Array }, [u, v]: [number, number]): number[] {
  const wrap = (i: number, n: number) => ((i % n) + n) % n;
  const x = u * baked.width - 0.5;
  const y = v * baked.height - 0.5;
  const [x0, y0] = [Math.floor(x), Math.floor(y)];
  const [wx, wy] = [x - x0, y - y0];
  const at = (i: number, j: number, c: number) => baked.values[(wrap(j, baked.height) * baked.width + wrap(i, baked.width)) * 3 + c];
  return [0, 1, 2].map((c) => (1 - wy) * ((1 - wx) * at(x0, y0, c) + wx * at(x0 + 1, y0, c)) + wy * ((1 - wx) * at(x0, y0 + 1, c) + wx * at(x0 + 1, y0 + 1, c)));
}

describe('uv transforms and the baker', () => {
  it("writes the format's T(offset) R(rotation) S(scale) as Mitsuba's scale, rotate(-r), translate", () => {
    const uv = { offset: [0.3, -1.2] as [number, number], scale: [2, 0.5] as [number, number], rotation: 35 };
    const elements = uvTransformElements(uv);
    expect(elements.map((e) => e.tag)).toEqual(['scale', 'rotate', 'translate']);
    const m = composed(asNodes(elements));
    for (const p of [[0, 0], [1, 0], [0.25, 0.75], [-3, 7]] as [number, number][]) {
      const [u, v] = apply(m, p);
      const [eu, ev] = transformUv(p, uv);
      expect(u).toBeCloseTo(eu, 12);
      expect(v).toBeCloseTo(ev, 12);
    }
    expect(uvTransformElements({ offset: [0, 0], scale: [1, 1], rotation: 0 })).toEqual([]);
  });

  it('bakes one image per distinct (image, input, channel, scale, cutoff), and names a missing image by the material', () => {
    const images = new Map([['t/a.png', testImage()]]);
    const baker = new MitsubaTextureBaker(images, (name) => `dir/${name}`);
    const textures = baker.forMaterial('meshes[2].material');
    const a = texture({ image: 't/a.png' });
    textures.bitmap('roughness', a, 'scalar');
    textures.bitmap('metallic', { ...a, uv: { offset: [1, 0], scale: [1, 1], rotation: 0 } }, 'scalar'); // same image: the uv is the XML's
    textures.bitmap('opacity', { ...a, scale: 0.5 }, 'scalar');
    textures.bitmap('opacity', { ...a, cutoff: 0.5 }, 'scalar');
    textures.bitmap('base_color', a, 'color');
    textures.bitmap('normalmap', a, 'normal');
    expect(baker.baked.map((b) => b.name)).toEqual(['tex0-a-r.pfm', 'tex1-a-r.pfm', 'tex2-a-r-cutoff.pfm', 'tex3-a-rgb.pfm', 'tex4-a-normal.pfm']);
    const xml = textures.bitmap('base_color', a, 'color');
    expect(xml.children.find((c) => c.attrs.some(([k, v]) => k === 'name' && v === 'filename'))!.attrs).toContainEqual(['value', 'dir/tex3-a-rgb.pfm']);
    expect(() => textures.bitmap('base_color', texture({ image: 'b.png' }), 'color')).toThrow(/meshes\[2\]\.material \(base_color\): the image "b\.png" is not among/);
  });
});

describe('integrator and mask', () => {
  const scene = (opacity: unknown): Scene =>
    parseSceneText(
      JSON.stringify({
        version: 3,
        camera: { position: [0, 1, 3], target: [0, 0, 0] },
        ground: { material: { type: 'principled', opacity } },
      }),
    );

  it('uses volpath when a material is see-through anywhere, with mask outermost', () => {
    expect(exportMitsuba(scene(1)).xml).toContain('<integrator type="path">');
    const constant = parseXml(exportMitsuba(scene(0.4)).xml);
    expect(only(constant, 'integrator').attrs.type).toBe('volpath');
    const mask = only(only(constant, 'shape'), 'bsdf');
    expect(mask.attrs.type).toBe('mask');
    expect(named(mask, 'opacity')).toMatchObject({ tag: 'float', attrs: { value: '0.4' } });

    const images = new Map([['a.png', testImage()]]);
    const textured = exportMitsuba(scene({ image: 'a.png', channel: 'a', cutoff: 0.5 }), { images });
    const root = parseXml(textured.xml);
    expect(only(root, 'integrator').attrs.type).toBe('volpath');
    const texturedMask = only(only(root, 'shape'), 'bsdf');
    expect(texturedMask.attrs.type).toBe('mask');
    const opacity = only(texturedMask, 'texture');
    expect(opacity.attrs.name).toBe('opacity');
    expect(named(opacity, 'filter_type')!.attrs.value).toBe('nearest');
    expect(textured.textures.map((t) => t.name)).toEqual(['tex0-a-a-cutoff.pfm']);
  });

  it("writes a textured emission as the area emitter's radiance texture (times color x intensity), and a constant opacity into the radiance", async () => {
    const mesh = (material: unknown) =>
      parseSceneText(JSON.stringify({ version: 3, camera: { position: [0, 1, 3], target: [0, 0, 0] }, meshes: [{ file: 'quad.obj', material }] }));
    const image = testImage();
    const images = new Map([['e.png', image]]);
    const options = { images, meshPath: () => 'quad.ply' };
    const emission = { color: { image: 'e.png', scale: [1, 0.5, 0.25] }, intensity: 4 };
    const textured = exportMitsuba(mesh({ type: 'principled', emission }), options);
    const emitter = only(only(parseXml(textured.xml), 'shape'), 'emitter');
    expect(emitter.attrs.type).toBe('area');
    expect(only(emitter, 'texture').attrs.name).toBe('radiance');
    const [baked] = textured.textures;
    expect(baked.name).toBe('tex0-e-rgb.pfm');
    baked.values.forEach((v, i) => expectFloat32(v, srgbToLinear(image.data[Math.floor(i / 3) * 4 + (i % 3)] / 255) * [4, 2, 1][i % 3]));

    const halfSeen = parseXml(exportMitsuba(mesh({ type: 'principled', opacity: 0.5, emission: { color: [1, 0.5, 0.25], intensity: 4 } }), options).xml);
    expect(only(only(only(halfSeen, 'shape'), 'emitter'), 'rgb').attrs.value).toBe('2, 1, 0.5');
    const halfTextured = exportMitsuba(mesh({ type: 'principled', opacity: 0.5, emission }), options);
    expect(Math.max(...halfTextured.textures[0].values)).toBeCloseTo(Math.max(...baked.values) / 2, 6);
  });

  it('refuses a textured scene without its images, naming the material', () => {
    expect(() => exportMitsuba(scene({ image: 'a.png' }))).toThrow(/ground\.material \(opacity\): the image "a\.png"/);
  });
});
