/**
 * Decodes a texture image file into RGBA at full precision (scene format
 * version 3, "Textures"). Pure TypeScript for PNG, OpenEXR and Radiance
 * .hdr, so the page's worker, the CLI's browser and the tests share it;
 * JPEG and WebP go to the browser's own decoder (`bitmap`).
 */
import { decode as decodePng, type DecodedPng } from 'fast-png';
import { AssetError } from '../assetError';
import { zeroInvalidTexels } from '../envmap/decode';
import { decodeExr } from '../envmap/exr';
import { decodeRgbe } from '../envmap/rgbe';
import type { EnvironmentImage } from '../types';
import { imageHeader, readPngHeader, type ImageHeader } from './header';
import { TEXEL_BYTES, type BitmapDecoder, type TexelEncoding, type TextureImage } from './image';
import { checkTextureSize, MAX_TEXTURE_BYTES } from './limits';
import { jpegExifOrientation, swapsSides, undoOrientation } from './orientation';

function fail(message: string): never {
  throw new AssetError(message);
}

const MIME = { jpeg: 'image/jpeg', webp: 'image/webp' } as const;

/**
 * Decodes an image file (checking imageHeader first). Throws AssetError
 * (message without the scene path) for an unknown, unsupported, corrupt,
 * truncated or oversized file.
 */
export async function decodeTextureImage(bytes: Uint8Array, bitmap?: BitmapDecoder): Promise<TextureImage> {
  const header = imageHeader(bytes);
  checkDecodedBytes(header, encodingOf(bytes, header));
  switch (header.format) {
    case 'png':
      return decodePngImage(bytes);
    case 'exr':
      return floatImage('exr', decodeExr(bytes, checkTextureSize));
    case 'hdr':
      return floatImage('hdr', decodeRgbe(bytes, checkTextureSize));
    case 'jpeg':
    case 'webp':
      return decodeBitmap(bytes, header, bitmap);
  }
}

function encodingOf(bytes: Uint8Array, header: ImageHeader): TexelEncoding {
  if (header.format === 'exr' || header.format === 'hdr') return 'f32';
  if (header.format === 'png' && readPngHeader(bytes).bitDepth === 16) return 'u16';
  return 'u8';
}

/** One image that alone exceeds the scene's budget is refused before it is decoded. */
function checkDecodedBytes(header: ImageHeader, encoding: TexelEncoding): void {
  const bytes = header.width * header.height * TEXEL_BYTES[encoding];
  if (bytes > MAX_TEXTURE_BYTES) {
    const mb = (n: number) => `${Math.round(n / 2 ** 20)} MB`;
    fail(`image is ${header.width}x${header.height} ${encoding === 'f32' ? 'float' : encoding === 'u16' ? '16-bit' : '8-bit'} RGBA, ${mb(bytes)} decoded, more than the ${mb(MAX_TEXTURE_BYTES)} a scene's images may take`);
  }
}

// ---------------------------------------------------------------- PNG

const GREY = 0;
const RGB = 2;
const PALETTE = 3;
const GREY_ALPHA = 4;
const RGBA = 6;

const ALLOWED_DEPTHS: Record<number, number[]> = {
  [GREY]: [1, 2, 4, 8, 16],
  [RGB]: [8, 16],
  [PALETTE]: [1, 2, 4, 8],
  [GREY_ALPHA]: [8, 16],
  [RGBA]: [8, 16],
};

function decodePngImage(bytes: Uint8Array): TextureImage {
  const { width, height, bitDepth, colorType, interlaced } = readPngHeader(bytes);
  if (!ALLOWED_DEPTHS[colorType]) fail(`corrupt PNG file (unknown colour type ${colorType})`);
  if (!ALLOWED_DEPTHS[colorType].includes(bitDepth)) fail(`corrupt PNG file (bit depth ${bitDepth} is not allowed for colour type ${colorType})`);
  // fast-png's Adam7 de-interlacing handles whole bytes only.
  if (interlaced && bitDepth < 8) fail(`interlaced PNG files with ${bitDepth} bits a channel are not supported (save it non-interlaced, or at 8 bits)`);
  let png: DecodedPng;
  try {
    png = decodePng(bytes, { checkCrc: true });
  } catch (error) {
    fail(`corrupt or truncated PNG file (${pngErrorMessage(error)})`);
  }
  if (png.width !== width || png.height !== height || png.depth !== bitDepth) fail('corrupt PNG file (decoded size differs from the header)');
  const encoding = bitDepth === 16 ? 'u16' : 'u8';
  if (colorType === RGBA && png.data.length === width * height * 4) return { width, height, format: 'png', encoding, data: png.data as Uint8Array | Uint16Array };
  const samples = sampleReader(png, colorType === PALETTE ? 1 : png.channels);
  const data = colorType === PALETTE ? paletteToRgba(png, samples) : samplesToRgba(png, colorType, samples);
  return { width, height, format: 'png', encoding, data };
}

function pngErrorMessage(error: unknown): string {
  const message = error instanceof Error ? error.message : String(error);
  // fast-png wraps zlib's error; its cause says what went wrong.
  const cause = error instanceof Error && error.cause instanceof Error ? ` ${error.cause.message}` : '';
  if (error instanceof RangeError || /offset is outside the bounds|out of bounds/i.test(message)) return 'the file ends early';
  return `${message}${cause}`;
}

/** Sample (x, y, channel) of the decoded rows, whatever the bit depth (1, 2 and 4 bits are packed into bytes, rows padded to a byte). */
function sampleReader(png: DecodedPng, channels: number): (x: number, y: number, c: number) => number {
  const { width, height, depth, data } = png;
  if (depth >= 8) {
    if (data.length !== width * height * channels) fail(`corrupt PNG file (${data.length} samples decoded, expected ${width * height * channels})`);
    return (x, y, c) => data[(y * width + x) * channels + c];
  }
  const rowBytes = Math.ceil((width * depth) / 8);
  if (data.length !== rowBytes * height) fail(`corrupt PNG file (${data.length} bytes of samples decoded, expected ${rowBytes * height})`);
  const perByte = 8 / depth;
  const mask = (1 << depth) - 1;
  return (x, y) => (data[y * rowBytes + Math.floor(x / perByte)] >> (8 - depth * (1 + (x % perByte)))) & mask;
}

/** Grey, grey+alpha, RGB and RGBA to RGBA at the file's precision; a tRNS colour key becomes alpha 0. */
function samplesToRgba(png: DecodedPng, colorType: number, sample: (x: number, y: number, c: number) => number): Uint8Array | Uint16Array {
  const { width, height, depth } = png;
  const out = depth === 16 ? new Uint16Array(width * height * 4) : new Uint8Array(width * height * 4);
  const opaque = depth === 16 ? 0xffff : 0xff;
  // Grey of 1, 2 or 4 bits is scaled to 8 bits exactly (the PNG specification's v * 255 / (2^depth - 1)).
  const scale = depth < 8 ? 255 / ((1 << depth) - 1) : 1;
  const key = png.transparency;
  const grey = colorType === GREY || colorType === GREY_ALPHA;
  const hasAlpha = colorType === GREY_ALPHA || colorType === RGBA;
  for (let y = 0, i = 0; y < height; y++) {
    for (let x = 0; x < width; x++, i += 4) {
      const r = sample(x, y, 0);
      const g = grey ? r : sample(x, y, 1);
      const b = grey ? r : sample(x, y, 2);
      let a = hasAlpha ? sample(x, y, grey ? 1 : 3) : opaque;
      if (key && !hasAlpha && (grey ? r === key[0] : r === key[0] && g === key[1] && b === key[2])) a = 0;
      out[i] = r * scale;
      out[i + 1] = g * scale;
      out[i + 2] = b * scale;
      out[i + 3] = a;
    }
  }
  return out;
}

/** Palette indices to the palette's RGB and its tRNS alpha (255 where it gives none). */
function paletteToRgba(png: DecodedPng, index: (x: number, y: number, c: number) => number): Uint8Array {
  const { width, height } = png;
  const palette = png.palette;
  if (!palette || palette.length === 0) fail('corrupt PNG file (an indexed-colour image without a PLTE palette)');
  const out = new Uint8Array(width * height * 4);
  for (let y = 0, i = 0; y < height; y++) {
    for (let x = 0; x < width; x++, i += 4) {
      const k = index(x, y, 0);
      const entry = palette[k];
      if (!entry) fail(`corrupt PNG file (palette index ${k} beyond the palette's ${palette.length} colours)`);
      out[i] = entry[0];
      out[i + 1] = entry[1];
      out[i + 2] = entry[2];
      out[i + 3] = entry.length > 3 ? entry[3] : 255;
    }
  }
  return out;
}

// ---------------------------------------------------------------- EXR, HDR

/** The environment maps' decoders give linear RGB (top row first); textures take RGBA with alpha 1. NaN and infinities become 0 as for maps. */
function floatImage(format: 'exr' | 'hdr', image: EnvironmentImage): TextureImage {
  zeroInvalidTexels(image.rgb);
  const { width, height, rgb } = image;
  const data = new Float32Array(width * height * 4);
  for (let p = 0; p < width * height; p++) {
    data[p * 4] = rgb[p * 3];
    data[p * 4 + 1] = rgb[p * 3 + 1];
    data[p * 4 + 2] = rgb[p * 3 + 2];
    data[p * 4 + 3] = 1;
  }
  return { width, height, format, encoding: 'f32', data };
}

// ---------------------------------------------------------------- JPEG, WebP

async function decodeBitmap(bytes: Uint8Array, header: ImageHeader, bitmap: BitmapDecoder | undefined): Promise<TextureImage> {
  const format = header.format as 'jpeg' | 'webp';
  if (!bitmap) fail(`JPEG/WebP images are decoded by the browser, and there is none here (this ${format === 'jpeg' ? 'JPEG' : 'WebP'} image needs the page or the CLI's browser; PNG, EXR and HDR decode anywhere)`);
  let decoded: Awaited<ReturnType<BitmapDecoder>>;
  try {
    decoded = await bitmap(bytes, MIME[format]);
  } catch (error) {
    if (error instanceof AssetError) throw error;
    fail(`corrupt or truncated ${format === 'jpeg' ? 'JPEG' : 'WebP'} file (the browser cannot decode it: ${(error as Error)?.message ?? String(error)})`);
  }
  const { width, height } = header;
  const orientation = format === 'jpeg' ? jpegExifOrientation(bytes) : 1;
  const [shownWidth, shownHeight] = swapsSides(orientation) ? [height, width] : [width, height];
  if (decoded.width !== shownWidth || decoded.height !== shownHeight) {
    fail(`the browser decoded this ${format === 'jpeg' ? 'JPEG' : 'WebP'} image as ${decoded.width}x${decoded.height}, where its header says ${width}x${height}${orientation === 1 ? '' : ` (EXIF orientation ${orientation})`}`);
  }
  if (decoded.data.length !== width * height * 4) fail(`the browser's decoder returned ${decoded.data.length} values for ${width}x${height} RGBA`);
  // Mitsuba reads a JPEG as stored; the browser has applied its EXIF orientation (./orientation.ts).
  const data = undoOrientation(decoded.data, width, height, orientation);
  return { width, height, format, encoding: 'u8', data };
}
