/**
 * OpenEXR (`.exr`) decoder: three.js's EXRLoader (maintained, used by every
 * three.js app that loads an environment; half and float channels,
 * uncompressed, RLE, ZIPS, ZIP, PIZ, PXR24, B44/B44A, DWAA and DWAB), in a
 * vendored copy with one fix (./vendor/EXRLoader.js: a corrupt Huffman
 * stream made it loop forever).
 *
 * Before handing the file over we read its header ourselves: the size limit
 * must hold before any pixel is decoded, and the scanline offset table must
 * point inside the file (EXRLoader reads past the end of a truncated PIZ or
 * DWA file as zeros instead of failing).
 */
import { EXRLoader } from './vendor/EXRLoader.js';
import { FloatType } from 'three';
import { AssetError } from '../assetError';
import type { EnvironmentImage } from '../types';
import { checkEnvironmentSize, type SizeCheck } from './limits';

const EXR_MAGIC = 20000630;
const COMPRESSIONS = ['NONE', 'RLE', 'ZIPS', 'ZIP', 'PIZ', 'PXR24', 'B44', 'B44A', 'DWAA', 'DWAB'];
/** Scanlines per chunk of each compression (OpenEXR's file layout). */
const LINES_PER_CHUNK = [1, 1, 1, 16, 32, 16, 32, 32, 32, 256];
const MAX_ATTRIBUTES = 1000;

function fail(message: string): never {
  throw new AssetError(message);
}

export interface ExrHeader {
  width: number;
  height: number;
  compression: string;
  channels: string[];
  tiled: boolean;
  /** Byte offset of the chunk offset table. */
  tableStart: number;
}

function readCString(bytes: Uint8Array, start: number, limit: number): { text: string; next: number } {
  const end = bytes.indexOf(0, start);
  if (end < 0 || end - start > limit) fail('truncated or corrupt OpenEXR header');
  let text = '';
  for (let i = start; i < end; i++) text += String.fromCharCode(bytes[i]);
  return { text, next: end + 1 };
}

function readChannelNames(view: DataView, start: number, end: number): string[] {
  const bytes = new Uint8Array(view.buffer, view.byteOffset, view.byteLength);
  const names: string[] = [];
  let pos = start;
  while (pos < end && bytes[pos] !== 0) {
    const name = readCString(bytes, pos, 255);
    names.push(name.text);
    pos = name.next + 16; // pixel type, pLinear, reserved, xSampling, ySampling
  }
  return names;
}

/** Walks the header's attributes (name, type, size, value) up to the empty name. */
export function readExrHeader(bytes: Uint8Array, checkSize: SizeCheck = checkEnvironmentSize): ExrHeader {
  if (bytes.length < 8) fail('truncated OpenEXR file (no header)');
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (view.getUint32(0, true) !== EXR_MAGIC) fail('not an OpenEXR file (bad magic number)');
  const flags = view.getUint32(4, true);
  if (flags & 0x800) fail('deep OpenEXR images are not supported');
  if (flags & 0x1000) fail('multi-part OpenEXR files are not supported');
  const nameLimit = flags & 0x400 ? 255 : 31;
  let pos = 8;
  let box: number[] | null = null;
  let compression = -1;
  let channels: string[] = [];
  for (let count = 0; ; count++) {
    if (pos >= bytes.length) fail('truncated OpenEXR header');
    if (bytes[pos] === 0) break;
    if (count > MAX_ATTRIBUTES) fail('corrupt OpenEXR header (too many attributes)');
    const name = readCString(bytes, pos, nameLimit);
    const type = readCString(bytes, name.next, nameLimit);
    if (type.next + 4 > bytes.length) fail('truncated OpenEXR header');
    const size = view.getInt32(type.next, true);
    const value = type.next + 4;
    if (size < 0 || value + size > bytes.length) fail('truncated or corrupt OpenEXR header');
    if (name.text === 'dataWindow' && type.text === 'box2i' && size === 16) {
      box = [0, 4, 8, 12].map((o) => view.getInt32(value + o, true));
    } else if (name.text === 'compression' && size === 1) {
      compression = bytes[value];
    } else if (name.text === 'channels' && type.text === 'chlist') {
      channels = readChannelNames(view, value, value + size);
    }
    pos = value + size;
  }
  if (!box) fail('corrupt OpenEXR header (no dataWindow)');
  if (compression < 0 || compression >= COMPRESSIONS.length) fail(`unsupported OpenEXR compression ${compression}`);
  const [xMin, yMin, xMax, yMax] = box;
  const width = xMax - xMin + 1;
  const height = yMax - yMin + 1;
  checkSize(width, height, fail);
  const hasRgb = ['R', 'G', 'B'].every((c) => channels.includes(c));
  if (!hasRgb && !channels.includes('Y')) fail(`OpenEXR file has no R, G, B (or Y) channels (it has ${channels.join(', ') || 'none'})`);
  return { width, height, compression: COMPRESSIONS[compression], channels, tiled: (flags & 0x200) !== 0, tableStart: pos + 1 };
}

/** Every chunk of a scanline file must start inside the file and its data end inside it. */
function checkChunks(bytes: Uint8Array, header: ExrHeader): void {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const chunks = Math.ceil(header.height / LINES_PER_CHUNK[COMPRESSIONS.indexOf(header.compression)]);
  if (header.tableStart + chunks * 8 > bytes.length) fail('truncated OpenEXR file (offset table ends early)');
  for (let i = 0; i < chunks; i++) {
    const offset = Number(view.getBigUint64(header.tableStart + i * 8, true));
    if (offset + 8 > bytes.length) fail('truncated OpenEXR file (a scanline chunk lies past the end)');
    const dataSize = view.getInt32(offset + 4, true);
    if (dataSize < 0 || offset + 8 + dataSize > bytes.length) fail('truncated OpenEXR file (a scanline chunk ends past the end)');
  }
}

export function decodeExr(bytes: Uint8Array, checkSize: SizeCheck = checkEnvironmentSize): EnvironmentImage {
  const header = readExrHeader(bytes, checkSize);
  if (!header.tiled) checkChunks(bytes, header);
  const buffer = bytes.slice().buffer; // EXRLoader wants an ArrayBuffer of the file alone
  let parsed: { width: number; height: number; data: ArrayLike<number> };
  try {
    parsed = new EXRLoader().setDataType(FloatType).parse(buffer) as typeof parsed;
  } catch (error) {
    fail(`corrupt OpenEXR file (${(error as Error).message.replace(/^THREE\.EXRLoader: /, '')})`);
  }
  const { width, height, data } = parsed;
  if (width !== header.width || height !== header.height || data.length !== width * height * 4) {
    fail('corrupt OpenEXR file (decoded size differs from the header)');
  }
  return { width, height, rgb: rgbaRowsToRgb(data, width, height) };
}

/** EXRLoader returns RGBA rows bottom to top (GL's order): drop alpha and put the top row first. */
function rgbaRowsToRgb(rgba: ArrayLike<number>, width: number, height: number): Float32Array {
  const rgb = new Float32Array(width * height * 3);
  for (let y = 0; y < height; y++) {
    const source = (height - 1 - y) * width * 4;
    const target = y * width * 3;
    for (let x = 0; x < width; x++) {
      rgb[target + x * 3] = rgba[source + x * 4];
      rgb[target + x * 3 + 1] = rgba[source + x * 4 + 1];
      rgb[target + x * 3 + 2] = rgba[source + x * 4 + 2];
    }
  }
  return rgb;
}
