/**
 * Where each texture image lives on the GPU: texture arrays of square atlas
 * pages, one array per storage format, each image at its own size (no
 * resampling to a common size) on a shelf of a page. The shader addresses
 * texels of an image by integer coordinates and does its own wrapping and
 * bilinear filtering (textures/texture.glsl: Mitsuba's `bitmap`), so images
 * need no gutters and can share pages. Pure: unit-tested without GL.
 *
 * Formats, by the image's encoding and the input it feeds:
 * - `srgb8`: an 8-bit image read as a color: SRGB8_ALPHA8, which texelFetch
 *   decodes per texel before the shader filters (the format's rule);
 * - `linear8`: an 8-bit image read as stored (scalars, normal maps): RGBA8;
 * - `float`: 16-bit PNGs and EXR/HDR images: RGBA32F (16-bit colour images
 *   are decoded from sRGB when uploaded; the values are exact in float).
 */
import type { TextureInput } from '../../scene/texture/texture';
import type { TextureImage } from '../../scene/texture/image';

export type AtlasFormat = 'srgb8' | 'linear8' | 'float';
export const ATLAS_FORMATS: readonly AtlasFormat[] = ['srgb8', 'linear8', 'float'];
export const ATLAS_BYTES_PER_TEXEL: Record<AtlasFormat, number> = { srgb8: 4, linear8: 4, float: 16 };

/** The storage format of an image feeding an input. */
export function atlasFormat(image: Pick<TextureImage, 'encoding'>, input: TextureInput): AtlasFormat {
  if (image.encoding !== 'u8') return 'float';
  return input === 'color' ? 'srgb8' : 'linear8';
}

/** An image's place: its page (layer) of its format's array and its rectangle there, at the size stored (maybe halved). */
export interface Placement {
  format: AtlasFormat;
  layer: number;
  x: number;
  y: number;
  width: number;
  height: number;
  /** Times the image was halved to fit the device (0: full size). */
  halvings: number;
}

export interface AtlasPage {
  /** Side of every page of the format's array. */
  size: number;
  layers: number;
}

export interface AtlasPlan {
  pages: Partial<Record<AtlasFormat, AtlasPage>>;
  /** By placementKey(image name, format). */
  placements: Map<string, Placement>;
  /** GPU bytes of all pages. */
  bytes: number;
  /** One per image stored at less than its size ("halved to fit this device"). */
  warnings: string[];
}

export interface DeviceLimits {
  maxTextureSize: number;
  maxArrayLayers: number;
}

export const placementKey = (image: string, format: AtlasFormat) => `${format}:${image}`;

/** An image to place: its name, format and size. */
export interface AtlasEntry {
  image: string;
  format: AtlasFormat;
  width: number;
  height: number;
}

/**
 * Places every entry (each name and format once). Pages are square, the
 * smallest power of two that holds the format's largest image (at most
 * the device's MAX_TEXTURE_SIZE); an image larger than that is halved until
 * it fits (a warning names it). Shelves: tallest images first, left to
 * right, a new shelf below when a row is full, a new page when a page is.
 */
export function planAtlas(entries: readonly AtlasEntry[], limits: DeviceLimits): AtlasPlan {
  const plan: AtlasPlan = { pages: {}, placements: new Map(), bytes: 0, warnings: [] };
  for (const format of ATLAS_FORMATS) {
    const unique = new Map<string, AtlasEntry>();
    for (const e of entries) if (e.format === format) unique.set(e.image, e);
    if (unique.size === 0) continue;
    const sized = [...unique.values()].map((e) => fitted(e, limits.maxTextureSize, plan.warnings));
    const largest = Math.max(...sized.map((e) => Math.max(e.width, e.height)));
    const size = Math.min(limits.maxTextureSize, 2 ** Math.ceil(Math.log2(largest)));
    const layers = placeOnShelves(sized, size, format, plan.placements);
    if (layers > limits.maxArrayLayers) throw new Error(`the scene's ${format} textures need ${layers} atlas pages of ${size}x${size}; this device allows ${limits.maxArrayLayers}`);
    plan.pages[format] = { size, layers };
    plan.bytes += size * size * layers * ATLAS_BYTES_PER_TEXEL[format];
  }
  return plan;
}

interface Sized extends AtlasEntry {
  halvings: number;
}

function fitted(e: AtlasEntry, maxSize: number, warnings: string[]): Sized {
  let { width, height } = e;
  let halvings = 0;
  while (width > maxSize || height > maxSize) {
    width = Math.max(1, Math.floor(width / 2));
    height = Math.max(1, Math.floor(height / 2));
    halvings++;
  }
  if (halvings > 0) warnings.push(`${e.image}: ${e.width}x${e.height} is larger than this device's ${maxSize}-texel textures: halved to ${width}x${height}`);
  return { ...e, width, height, halvings };
}

/** Shelf packing; returns the pages used. */
function placeOnShelves(images: Sized[], size: number, format: AtlasFormat, out: Map<string, Placement>): number {
  const order = [...images].sort((a, b) => b.height - a.height || b.width - a.width || (a.image < b.image ? -1 : 1));
  let layer = 0;
  let x = 0;
  let y = 0;
  let shelf = 0;
  for (const img of order) {
    if (x + img.width > size) [x, y, shelf] = [0, y + shelf, 0];
    if (y + img.height > size) [layer, x, y, shelf] = [layer + 1, 0, 0, 0];
    out.set(placementKey(img.image, format), { format, layer, x, y, width: img.width, height: img.height, halvings: img.halvings });
    x += img.width;
    shelf = Math.max(shelf, img.height);
  }
  return layer + 1;
}
