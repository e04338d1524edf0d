/**
 * Textures in the Mitsuba export, baked the way the version-3 references
 * were made (scene format, "References for version 3"): factor x texture,
 * sRGB decoded, channels split into single-channel images, written as float
 * PFM files that Mitsuba's `bitmap` reads with `raw` (no decoding: the bake
 * did it) and filters exactly as the format's lookup does (bilinear between
 * texel centres, repeat; test/fixtures/bitmap-lookups/README.md).
 *
 * Why the bake gives Mitsuba the format's value: the bilinear filter is
 * linear, so it commutes with the factor and with a normal map's affine
 * re-encoding, and an 8-bit or 16-bit colour texel is decoded before
 * filtering in both. Mitsuba cannot pick a channel for a scalar input
 * (`eval_1` of an RGB texture is its luminance), hence one channel per image.
 *
 * The one input the bake cannot give exactly is a scalar's `cutoff`, which
 * the renderer applies after filtering and Mitsuba has no way to: see
 * bakeCutout (an upsampled, thresholded image filtered `nearest`).
 *
 * Pure: no DOM, no Node APIs (the CLI writes the files).
 */
import type { MitsubaTextures } from '../materials/kind';
import { encodePfmChannels } from '../image/pfm';
import { srgbToLinear } from './color';
import { bool, el, num, str, type XmlNode } from './mitsubaXml';
import type { TextureImage } from './texture/image';
import { CHANNELS, scaleColor, type Texture, type TextureInput } from './texture/texture';

/** A float image the export refers to. */
export interface BakedTexture {
  /** Its file name, unique within one export: `tex<k>-<image's stem>-<use>.pfm`. */
  name: string;
  width: number;
  height: number;
  channels: 1 | 3;
  /** `channels` floats per texel, rows from the top. */
  values: Float32Array;
  /** Mitsuba's `filter_type`: bilinear, or nearest for a cut-out's upsampled image. */
  filter: 'bilinear' | 'nearest';
}

export type BakedImage = Omit<BakedTexture, 'name'>;

/** The PFM file of a baked texture (`Pf` for one channel, `PF` for three). */
export const bakedTextureFile = (b: BakedTexture): Uint8Array => encodePfmChannels(b.width, b.height, b.channels, b.values);

/** A texel's channel as stored, in [0, 1] for 8 and 16 bits (the format's "as stored"). */
function storedReader(image: TextureImage): (texel: number, channel: number) => number {
  const { data, encoding } = image;
  const unit = encoding === 'u8' ? 1 / 255 : encoding === 'u16' ? 1 / 65535 : 1;
  return (texel, channel) => data[texel * 4 + channel] * unit;
}

/** A colour input: RGB, 8 and 16 bits decoded from sRGB per texel (float images are linear), times the scale. */
export function bakeColor(image: TextureImage, scale: readonly number[]): BakedImage {
  const read = storedReader(image);
  const decode = image.encoding === 'f32' ? (x: number) => x : srgbToLinear;
  const texels = image.width * image.height;
  const values = new Float32Array(texels * 3);
  for (let t = 0; t < texels; t++) for (let c = 0; c < 3; c++) values[t * 3 + c] = decode(read(t, c)) * scale[c];
  return { width: image.width, height: image.height, channels: 3, values, filter: 'bilinear' };
}

/** A scalar input: one channel as stored, times the scale. */
export function bakeScalar(image: TextureImage, channel: number, scale: number): BakedImage {
  const read = storedReader(image);
  const texels = image.width * image.height;
  const values = new Float32Array(texels);
  for (let t = 0; t < texels; t++) values[t] = read(t, channel) * scale;
  return { width: image.width, height: image.height, channels: 1, values, filter: 'bilinear' };
}

/**
 * A normal map: RGB as stored, re-encoded as `rgb' = ((2 rgb - 1) * (s, s, 1)
 * + 1) / 2`, so that Mitsuba's `normalmap` (which takes `2 rgb' - 1` of the
 * filtered value and normalizes it) finds the format's `normalize((2 rgb -
 * 1) * (s, s, 1))`: the re-encoding is affine, so filtering commutes with it.
 */
export function bakeNormalMap(image: TextureImage, scale: number): BakedImage {
  const read = storedReader(image);
  const factor = [scale, scale, 1];
  const texels = image.width * image.height;
  const values = new Float32Array(texels * 3);
  for (let t = 0; t < texels; t++) for (let c = 0; c < 3; c++) values[t * 3 + c] = ((2 * read(t, c) - 1) * factor[c] + 1) / 2;
  return { width: image.width, height: image.height, channels: 3, values, filter: 'bilinear' };
}

/** At most this many texels in a cut-out's upsampled image (16 MB of floats). */
const CUTOUT_TEXELS = 1 << 22;
/** Fine texels per source texel along each side of a cut-out's image (1 to 4, as its size allows). */
export function cutoutFactor(width: number, height: number): number {
  return Math.max(1, Math.min(4, Math.floor(Math.sqrt(CUTOUT_TEXELS / (width * height)))));
}

/**
 * A scalar input with `cutoff`: the renderer thresholds the filtered value
 * (1 where it is at least `cutoff`, 0 below, then times the scale), which no
 * Mitsuba texture can do. The bake samples the format's filtered value at
 * the centres of an image `cutoutFactor` times finer, thresholds each, and
 * has Mitsuba read it `nearest`: every value is then 0 or the scale, as in
 * the renderer, and an edge of the cut-out lies within half a fine texel
 * (1/8 of a source texel at factor 4) of the renderer's. So the export is
 * approximate there, at the edges only.
 */
export function bakeCutout(image: TextureImage, channel: number, scale: number, cutoff: number): BakedImage {
  const read = storedReader(image);
  const { width, height } = image;
  const k = cutoutFactor(width, height);
  const [fineWidth, fineHeight] = [width * k, height * k];
  const values = new Float32Array(fineWidth * fineHeight);
  const wrap = (i: number, n: number) => ((i % n) + n) % n;
  // Fine texel I's centre, in source texel units minus the half texel: the bilinear filter's position.
  const position = (i: number) => (i + 0.5) / k - 0.5;
  for (let fy = 0; fy < fineHeight; fy++) {
    const y = position(fy);
    const y0 = Math.floor(y);
    const wy = y - y0;
    const [r0, r1] = [wrap(y0, height) * width, wrap(y0 + 1, height) * width];
    for (let fx = 0; fx < fineWidth; fx++) {
      const x = position(fx);
      const x0 = Math.floor(x);
      const wx = x - x0;
      const [c0, c1] = [wrap(x0, width), wrap(x0 + 1, width)];
      const top = (1 - wx) * read(r0 + c0, channel) + wx * read(r0 + c1, channel);
      const bottom = (1 - wx) * read(r1 + c0, channel) + wx * read(r1 + c1, channel);
      const filtered = (1 - wy) * top + wy * bottom;
      values[fy * fineWidth + fx] = filtered >= cutoff ? scale : 0;
    }
  }
  return { width: fineWidth, height: fineHeight, channels: 1, values, filter: 'nearest' };
}

/** The image a texture feeding `input` is baked into. */
export function bakeTexture(image: TextureImage, texture: Texture, input: TextureInput): BakedImage {
  if (input === 'color') return bakeColor(image, scaleColor(texture));
  if (input === 'normal') return bakeNormalMap(image, texture.scale as number);
  const channel = CHANNELS.indexOf(texture.channel);
  const scale = texture.scale as number;
  return texture.cutoff === undefined ? bakeScalar(image, channel, scale) : bakeCutout(image, channel, scale, texture.cutoff);
}

/**
 * The `to_uv` elements of a texture's `uv`: the format's `T(offset) *
 * R(rotation) * S(scale)` is Mitsuba's `translate(offset) * rotate(-rotation)
 * * scale(scale)` (Mitsuba's 2-D rotation turns the other way), each XML
 * element left-multiplying the ones before it; identities are left out.
 */
export function uvTransformElements(uv: Texture['uv']): XmlNode[] {
  const out: XmlNode[] = [];
  if (uv.scale[0] !== 1 || uv.scale[1] !== 1) out.push(el('scale', { x: num(uv.scale[0]), y: num(uv.scale[1]) }));
  if (uv.rotation !== 0) out.push(el('rotate', { z: '1', angle: num(-uv.rotation) }));
  if (uv.offset[0] !== 0 || uv.offset[1] !== 0) out.push(el('translate', { x: num(uv.offset[0]), y: num(uv.offset[1]) }));
  return out;
}

/** What a use of an image is called in its file name. */
function useName(texture: Texture, input: TextureInput): string {
  if (input === 'color') return 'rgb';
  if (input === 'normal') return 'normal';
  return texture.cutoff === undefined ? texture.channel : `${texture.channel}-cutoff`;
}

/** An image's file name without folders and extension, in characters any file system takes. */
function stem(image: string): string {
  const base = image.split(/[\\/]/).pop()!.replace(/\.[^.]*$/, '');
  return base.replace(/[^A-Za-z0-9_-]/g, '_').slice(0, 40) || 'image';
}

/**
 * Bakes the textures of one export, each distinct (image, input, channel,
 * scale, cutoff) once, and writes their `bitmap` elements.
 */
export class MitsubaTextureBaker {
  private readonly bakes = new Map<string, BakedTexture>();

  /**
   * `images`: the scene's decoded images by name as written (SceneAssets.images);
   * `path`: the file name the XML gives a baked image (default: its name).
   */
  constructor(
    private readonly images: ReadonlyMap<string, TextureImage> | undefined,
    private readonly path: (name: string) => string = (name) => name,
  ) {}

  /**
   * The textures of the material at scene path `where` (for errors), on a
   * surface whose Mitsuba coordinates `surfaceUv` (to_uv elements, applied
   * first) turns into the format's (the ground's: see mitsuba.ts).
   */
  forMaterial(where: string, surfaceUv: readonly XmlNode[] = []): MitsubaTextures {
    return { bitmap: (name, texture, input) => this.bitmap(where, name, texture, input, surfaceUv) };
  }

  /** Every image baked so far, in the order the XML first names them. */
  get baked(): BakedTexture[] {
    return [...this.bakes.values()];
  }

  private bitmap(where: string, name: string, texture: Texture, input: TextureInput, surfaceUv: readonly XmlNode[]): XmlNode {
    const baked = this.bake(where, name, texture, input);
    const transform = [...surfaceUv, ...uvTransformElements(texture.uv)];
    return el('texture', { type: 'bitmap', name }, [
      str('filename', this.path(baked.name)),
      bool('raw', true),
      str('filter_type', baked.filter),
      str('wrap_mode', 'repeat'),
      ...(transform.length > 0 ? [el('transform', { name: 'to_uv' }, transform)] : []),
    ]);
  }

  private bake(where: string, name: string, texture: Texture, input: TextureInput): BakedTexture {
    const scalar = input === 'scalar';
    const key = JSON.stringify([texture.image, input, scalar ? texture.channel : null, texture.scale, scalar ? (texture.cutoff ?? null) : null]);
    const known = this.bakes.get(key);
    if (known) return known;
    const image = this.images?.get(texture.image);
    if (!image) {
      throw new Error(`toMitsubaXml: ${where} (${name}): the image ${JSON.stringify(texture.image)} is not among the export's images (pass the scene's SceneAssets.images)`);
    }
    const baked = { name: `tex${this.bakes.size}-${stem(texture.image)}-${useName(texture, input)}.pfm`, ...bakeTexture(image, texture, input) };
    this.bakes.set(key, baked);
    return baked;
  }
}
