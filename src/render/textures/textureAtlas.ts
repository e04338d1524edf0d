/**
 * The GPU side of the texture atlas (atlas.ts plans it): one
 * TEXTURE_2D_ARRAY per storage format the scene uses, each image uploaded
 * into its rectangle once. Re-planned and re-uploaded only when the set of
 * (image, format) pairs changes; material edits that keep the images reuse it.
 */
import { srgbToLinear } from '../../scene/color';
import type { TextureImage } from '../../scene/texture/image';
import type { TextureInput } from '../../scene/texture/texture';
import type { Program } from '../gl/program';
import { TEXTURE_UNITS } from '../gl/textureUnits';
import { ATLAS_FORMATS, atlasFormat, planAtlas, placementKey, type AtlasEntry, type AtlasFormat, type AtlasPlan, type Placement } from './atlas';

const UNIFORMS: Record<AtlasFormat, string> = { srgb8: 'uTexturesSrgb8', linear8: 'uTexturesLinear8', float: 'uTexturesFloat' };
const UNITS: Record<AtlasFormat, number> = { srgb8: TEXTURE_UNITS.texturesSrgb8, linear8: TEXTURE_UNITS.texturesLinear8, float: TEXTURE_UNITS.texturesFloat };

/** A texture the scene reads: its image's name and the input it feeds. */
export interface TextureUse {
  image: string;
  input: TextureInput;
}

export class TextureAtlas {
  private key = '';
  private plan: AtlasPlan | null = null;
  private arrays = new Map<AtlasFormat, WebGLTexture>();
  private images = new Map<string, TextureImage>();

  constructor(private readonly gl: WebGL2RenderingContext) {}

  /** GPU bytes of the atlas pages. */
  get bytes(): number {
    return this.plan?.bytes ?? 0;
  }

  /** Images stored smaller than their size on this device. */
  get warnings(): readonly string[] {
    return this.plan?.warnings ?? [];
  }

  /** Plans and uploads the atlas for `uses` (unless it holds exactly these already). */
  set(uses: readonly TextureUse[], images: ReadonlyMap<string, TextureImage>): void {
    const entries = uniqueEntries(uses, images);
    const key = JSON.stringify(entries.map((e) => [e.image, e.format]));
    if (key === this.key && entries.every((e) => this.images.get(imageName(e.image)) === images.get(imageName(e.image)))) return;
    this.dispose();
    this.key = key;
    if (entries.length === 0) return;
    const gl = this.gl;
    this.plan = planAtlas(entries, { maxTextureSize: gl.getParameter(gl.MAX_TEXTURE_SIZE), maxArrayLayers: gl.getParameter(gl.MAX_ARRAY_TEXTURE_LAYERS) });
    for (const format of ATLAS_FORMATS) {
      const page = this.plan.pages[format];
      if (page) this.arrays.set(format, this.createArray(format, page.size, page.layers));
    }
    for (const e of entries) {
      const name = imageName(e.image);
      const image = images.get(name)!;
      this.images.set(name, image);
      this.upload(this.plan.placements.get(placementKey(e.image, e.format))!, image, e.image !== name);
    }
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, null);
  }

  /** Where the image of a texture feeding `input` is. */
  placement(image: string, input: TextureInput): Placement {
    const decoded = this.images.get(image)!;
    const p = this.plan?.placements.get(placementKey(entryName(image, decoded, input), atlasFormat(decoded, input)));
    if (!p) throw new Error(`texture ${image} is not in the atlas`);
    return p;
  }

  bind(program: Program): void {
    const gl = this.gl;
    for (const [format, texture] of this.arrays) {
      gl.activeTexture(gl.TEXTURE0 + UNITS[format]);
      gl.bindTexture(gl.TEXTURE_2D_ARRAY, texture);
      program.setUniforms({ [UNIFORMS[format]]: UNITS[format] }, { [UNIFORMS[format]]: 'sampler2DArray' });
    }
  }

  dispose(): void {
    for (const texture of this.arrays.values()) this.gl.deleteTexture(texture);
    this.arrays.clear();
    this.images.clear();
    this.plan = null;
    this.key = '';
  }

  private createArray(format: AtlasFormat, size: number, layers: number): WebGLTexture {
    const gl = this.gl;
    const texture = gl.createTexture()!;
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, texture);
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    const internal = format === 'srgb8' ? gl.SRGB8_ALPHA8 : format === 'linear8' ? gl.RGBA8 : gl.RGBA32F;
    gl.texStorage3D(gl.TEXTURE_2D_ARRAY, 1, internal, size, size, layers);
    return texture;
  }

  private upload(p: Placement, image: TextureImage, decodeSrgb: boolean): void {
    const gl = this.gl;
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, this.arrays.get(p.format)!);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    const texels = storedTexels(image, p, decodeSrgb);
    const type = p.format === 'float' ? gl.FLOAT : gl.UNSIGNED_BYTE;
    gl.texSubImage3D(gl.TEXTURE_2D_ARRAY, 0, p.x, p.y, p.layer, p.width, p.height, 1, gl.RGBA, type, texels);
  }
}

function uniqueEntries(uses: readonly TextureUse[], images: ReadonlyMap<string, TextureImage>): AtlasEntry[] {
  const out = new Map<string, AtlasEntry>();
  for (const use of uses) {
    const image = images.get(use.image);
    if (!image) throw new Error(`texture image ${use.image} is not loaded`);
    const format = atlasFormat(image, use.input);
    const name = entryName(use.image, image, use.input);
    out.set(placementKey(name, format), { image: name, format, width: image.width, height: image.height });
  }
  return [...out.values()].sort((a, b) => (a.image < b.image ? -1 : a.image > b.image ? 1 : a.format < b.format ? -1 : 1));
}

/**
 * The texels as the atlas stores them: 8-bit as is; 16-bit as float, sRGB-
 * decoded for colour inputs (the `float` format then holds linear values);
 * float as is. Halved images are box-filtered 2x2 per halving.
 */
function storedTexels(image: TextureImage, p: Placement, decodeSrgb: boolean): Uint8Array | Float32Array {
  let data: Uint8Array | Float32Array = image.data instanceof Uint16Array ? sixteenBitTexels(image.data, decodeSrgb) : image.data;
  let [w, h] = [image.width, image.height];
  for (let i = 0; i < p.halvings; i++) [data, w, h] = halve(data, w, h);
  return data;
}

/**
 * A 16-bit PNG feeding a colour input is sRGB-encoded, as Mitsuba reads it
 * (RGB decoded, alpha not): the float atlas then holds a decoded copy of
 * its own, under the name entryName gives it.
 */
const SRGB_COPY = '\u0000srgb';
const entryName = (image: string, decoded: TextureImage, input: TextureInput) => (decoded.encoding === 'u16' && input === 'color' ? image + SRGB_COPY : image);
const imageName = (entry: string) => (entry.endsWith(SRGB_COPY) ? entry.slice(0, -SRGB_COPY.length) : entry);

function sixteenBitTexels(data: Uint16Array, decodeSrgb: boolean): Float32Array {
  const out = new Float32Array(data.length);
  for (let i = 0; i < data.length; i++) out[i] = decodeSrgb && i % 4 !== 3 ? srgbToLinear(data[i] / 65535) : data[i] / 65535;
  return out;
}

function halve(data: Uint8Array | Float32Array, w: number, h: number): [Uint8Array | Float32Array, number, number] {
  const [nw, nh] = [Math.max(1, w >> 1), Math.max(1, h >> 1)];
  const out = data instanceof Uint8Array ? new Uint8Array(nw * nh * 4) : new Float32Array(nw * nh * 4);
  for (let y = 0; y < nh; y++)
    for (let x = 0; x < nw; x++)
      for (let c = 0; c < 4; c++) {
        let sum = 0;
        for (const [dx, dy] of [[0, 0], [1, 0], [0, 1], [1, 1]]) sum += data[(Math.min(h - 1, 2 * y + dy) * w + Math.min(w - 1, 2 * x + dx)) * 4 + c];
        out[(y * nw + x) * 4 + c] = data instanceof Uint8Array ? Math.round(sum / 4) : sum / 4;
      }
  return [out, nw, nh];
}
