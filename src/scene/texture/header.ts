/**
 * A texture image's format and size from its first bytes, before any texel
 * is decoded: the size limit must hold before a decoder allocates anything
 * (a PNG header of 33 bytes can claim 100000 x 100000 texels).
 *
 * Formats are told apart by their signatures, never by the file's name.
 */
import { AssetError } from '../assetError';
import { readExrHeader } from '../envmap/exr';
import { readRgbeHeader } from '../envmap/rgbe';
import type { ImageFormat } from './image';
import { checkTextureSize } from './limits';

function fail(message: string): never {
  throw new AssetError(message);
}

function startsWith(bytes: Uint8Array, signature: ArrayLike<number>, at = 0): boolean {
  if (bytes.length < at + signature.length) return false;
  for (let i = 0; i < signature.length; i++) if (bytes[at + i] !== signature[i]) return false;
  return true;
}

const ascii = (text: string) => Array.from(text, (c) => c.charCodeAt(0));

const PNG_SIGNATURE = [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a];
const JPEG_SIGNATURE = [0xff, 0xd8, 0xff];
const EXR_SIGNATURE = [0x76, 0x2f, 0x31, 0x01];
const RGBE_SIGNATURE = ascii('#?');
const KTX2_SIGNATURE = [0xab, 0x4b, 0x54, 0x58, 0x20, 0x32, 0x30, 0xbb, 0x0d, 0x0a, 0x1a, 0x0a];

/** Formats recognised only to name them in the error. */
const UNSUPPORTED: { name: string; signature: number[]; at?: number }[] = [
  { name: 'KTX (version 1)', signature: [0xab, 0x4b, 0x54, 0x58, 0x20, 0x31, 0x31, 0xbb] },
  { name: 'GIF', signature: ascii('GIF8') },
  { name: 'TIFF', signature: [0x49, 0x49, 0x2a, 0x00] },
  { name: 'TIFF', signature: [0x4d, 0x4d, 0x00, 0x2a] },
  { name: 'DDS', signature: ascii('DDS ') },
  { name: 'AVIF', signature: ascii('ftypavif'), at: 4 },
  { name: 'HEIF', signature: ascii('ftyphei'), at: 4 },
];

export interface ImageHeader {
  format: ImageFormat;
  width: number;
  height: number;
}

/** A PNG's IHDR fields that the decoder needs besides the size. */
export interface PngHeader extends ImageHeader {
  bitDepth: number;
  colorType: number;
  interlaced: boolean;
}

/**
 * Format and size from the first bytes, before any decoding; throws
 * AssetError for an unknown format, KTX2, a truncated header, or a side over
 * MAX_TEXTURE_SIDE.
 */
export function imageHeader(bytes: Uint8Array): ImageHeader {
  if (bytes.length === 0) fail('the file is empty');
  let header: ImageHeader;
  if (startsWith(bytes, PNG_SIGNATURE)) header = readPngHeader(bytes);
  else if (startsWith(bytes, JPEG_SIGNATURE)) header = readJpegHeader(bytes);
  else if (startsWith(bytes, ascii('RIFF')) && startsWith(bytes, ascii('WEBP'), 8)) header = readWebpHeader(bytes);
  else if (startsWith(bytes, EXR_SIGNATURE)) header = { format: 'exr', ...readExrHeader(bytes, checkTextureSize) };
  else if (startsWith(bytes, RGBE_SIGNATURE)) header = { format: 'hdr', ...readRgbeHeader(bytes, checkTextureSize) };
  else if (startsWith(bytes, KTX2_SIGNATURE)) {
    fail('KTX2/Basis images are not supported: convert the texture to PNG, JPEG or WebP (e.g. with `ktx extract` or gltf-transform)');
  } else {
    const known = UNSUPPORTED.find((f) => startsWith(bytes, f.signature, f.at));
    if (known) fail(`${known.name} images are not supported (PNG, JPEG, WebP, OpenEXR and Radiance .hdr are)`);
    fail('not a PNG, JPEG, WebP, OpenEXR or Radiance .hdr image (its first bytes match none of them)');
  }
  checkTextureSize(header.width, header.height, fail);
  return { format: header.format, width: header.width, height: header.height };
}

/** The IHDR chunk, which the PNG specification puts first. */
export function readPngHeader(bytes: Uint8Array): PngHeader {
  if (bytes.length < 33) fail('truncated PNG file (no complete IHDR header)');
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (view.getUint32(8) !== 13 || !startsWith(bytes, ascii('IHDR'), 12)) fail('corrupt PNG file (it does not start with an IHDR chunk)');
  const header: PngHeader = {
    format: 'png',
    width: view.getUint32(16),
    height: view.getUint32(20),
    bitDepth: bytes[24],
    colorType: bytes[25],
    interlaced: bytes[28] === 1,
  };
  checkTextureSize(header.width, header.height, fail);
  return header;
}

/** Start-of-frame markers (SOF0..SOF15 less DHT, JPG and DAC), which hold the size. */
function isStartOfFrame(marker: number): boolean {
  return marker >= 0xc0 && marker <= 0xcf && marker !== 0xc4 && marker !== 0xc8 && marker !== 0xcc;
}

/** Walks the marker segments up to the first start-of-frame. */
function readJpegHeader(bytes: Uint8Array): ImageHeader {
  const truncated = () => fail('truncated JPEG file (it ends before the frame header that gives the size)');
  let pos = 2;
  for (;;) {
    if (pos >= bytes.length) truncated();
    if (bytes[pos] !== 0xff) fail('corrupt JPEG file (a marker segment is expected)');
    while (bytes[pos] === 0xff) if (++pos >= bytes.length) truncated(); // fill bytes
    const marker = bytes[pos++];
    if (marker === 0x01 || (marker >= 0xd0 && marker <= 0xd8)) continue; // no length
    if (marker === 0xd9 || marker === 0xda) fail('corrupt JPEG file (no frame header before the image data)');
    if (pos + 2 > bytes.length) truncated();
    const length = (bytes[pos] << 8) | bytes[pos + 1];
    if (length < 2) fail('corrupt JPEG file (a marker segment is shorter than its length field)');
    if (isStartOfFrame(marker)) {
      if (pos + 7 > bytes.length) truncated();
      const height = (bytes[pos + 3] << 8) | bytes[pos + 4];
      const width = (bytes[pos + 5] << 8) | bytes[pos + 6];
      if (height === 0) fail('JPEG files whose height is given after the image data (DNL marker) are not supported');
      return { format: 'jpeg', width, height };
    }
    pos += length;
  }
}

/** RIFF "WEBP" with a VP8 (lossy), VP8L (lossless) or VP8X (extended) first chunk. */
function readWebpHeader(bytes: Uint8Array): ImageHeader {
  const truncated = () => fail('truncated WebP file (it ends before the size)');
  if (bytes.length < 16) truncated();
  const chunk = String.fromCharCode(...bytes.subarray(12, 16));
  const b = (i: number) => bytes[i];
  if (chunk === 'VP8 ') {
    if (bytes.length < 30) truncated();
    if (!startsWith(bytes, [0x9d, 0x01, 0x2a], 23)) fail('corrupt WebP file (bad VP8 start code)');
    return { format: 'webp', width: (b(26) | (b(27) << 8)) & 0x3fff, height: (b(28) | (b(29) << 8)) & 0x3fff };
  }
  if (chunk === 'VP8L') {
    if (bytes.length < 25) truncated();
    if (b(20) !== 0x2f) fail('corrupt WebP file (bad VP8L signature)');
    const width = 1 + (((b(22) & 0x3f) << 8) | b(21));
    const height = 1 + (((b(24) & 0x0f) << 10) | (b(23) << 2) | ((b(22) & 0xc0) >> 6));
    return { format: 'webp', width, height };
  }
  if (chunk === 'VP8X') {
    if (bytes.length < 30) truncated();
    return { format: 'webp', width: 1 + (b(24) | (b(25) << 8) | (b(26) << 16)), height: 1 + (b(27) | (b(28) << 8) | (b(29) << 16)) };
  }
  fail(`corrupt WebP file (unknown first chunk "${chunk.replace(/[^\x20-\x7e]/g, '?')}")`);
}
