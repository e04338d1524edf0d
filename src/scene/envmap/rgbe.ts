/**
 * Radiance RGBE (`.hdr`) decoder: flat and new-style run-length-encoded
 * scanlines (the two that every writer produces, per Greg Ward's format
 * notes and Bruce Walter's rgbe.c).
 *
 * Written here rather than taken from three.js's HDRLoader because that one
 * silently fills the rest of a truncated RLE file with black, accepts a flat
 * file of any length, and converts with m * 2^(e-128) / 255 where Radiance,
 * rgbe.c and Mitsuba 3 (whose renders are the references) use
 * m * 2^(e-136): a 0.4 % difference in every texel.
 */
import { AssetError } from '../assetError';
import type { EnvironmentImage } from '../types';
import { checkEnvironmentSize, type SizeCheck } from './limits';

const MAX_HEADER_BYTES = 64 * 1024;

function fail(message: string): never {
  throw new AssetError(message);
}

export interface RgbeHeader {
  width: number;
  height: number;
  /** Byte offset of the first scanline. */
  dataStart: number;
}

/** Reads one '\n'-terminated line starting at `start`; null when there is none. */
function readLine(bytes: Uint8Array, start: number): { text: string; next: number } | null {
  const end = bytes.indexOf(0x0a, start);
  if (end < 0 || end - start > MAX_HEADER_BYTES) return null;
  let text = '';
  for (let i = start; i < end; i++) text += String.fromCharCode(bytes[i]);
  return { text, next: end + 1 };
}

export function readRgbeHeader(bytes: Uint8Array, checkSize: SizeCheck = checkEnvironmentSize): RgbeHeader {
  let line = readLine(bytes, 0);
  if (!line || !/^#\?(RADIANCE|RGBE)\b/.test(line.text)) fail('not a Radiance .hdr file (it must start with "#?RADIANCE" or "#?RGBE")');
  let format: string | null = null;
  // Header lines up to the blank line that ends them.
  for (;;) {
    line = readLine(bytes, line.next);
    if (!line) fail('truncated Radiance header (no blank line before the image size)');
    if (line.text.trim() === '') break;
    const match = /^FORMAT=(.*)$/.exec(line.text);
    if (match) format = match[1].trim();
  }
  if (format !== null && format !== '32-bit_rle_rgbe') fail(`unsupported Radiance pixel format "${format}" (only 32-bit_rle_rgbe)`);
  const sizeLine = readLine(bytes, line.next);
  if (!sizeLine) fail('truncated Radiance header (no image size line)');
  const size = /^\s*-Y\s+(\d+)\s+\+X\s+(\d+)\s*$/.exec(sizeLine.text);
  if (!size) fail(`unsupported Radiance image size line "${sizeLine.text.slice(0, 40)}" (only the standard "-Y height +X width")`);
  const height = Number(size[1]);
  const width = Number(size[2]);
  checkSize(width, height, fail);
  return { width, height, dataStart: sizeLine.next };
}

/** Decodes one new-style RLE scanline (four channel planes) into `plane`; returns the next offset. */
function readRleScanline(bytes: Uint8Array, start: number, width: number, plane: Uint8Array): number {
  let pos = start + 4;
  for (let channel = 0; channel < 4; channel++) {
    const base = channel * width;
    let x = 0;
    while (x < width) {
      if (pos >= bytes.length) fail('truncated Radiance file (scanline data ends early)');
      let count = bytes[pos++];
      if (count > 128) {
        count -= 128;
        if (pos >= bytes.length) fail('truncated Radiance file (scanline data ends early)');
        if (x + count > width) fail('corrupt Radiance file (run overruns its scanline)');
        plane.fill(bytes[pos++], base + x, base + x + count);
      } else {
        if (count === 0 || x + count > width) fail('corrupt Radiance file (bad run length)');
        if (pos + count > bytes.length) fail('truncated Radiance file (scanline data ends early)');
        plane.set(bytes.subarray(pos, pos + count), base + x);
        pos += count;
      }
      x += count;
    }
  }
  return pos;
}

function isRleScanline(bytes: Uint8Array, pos: number, width: number): boolean {
  if (width < 8 || width > 0x7fff || pos + 4 > bytes.length) return false;
  return bytes[pos] === 2 && bytes[pos + 1] === 2 && (bytes[pos + 2] & 0x80) === 0;
}

/** 2^(e - 136) for each exponent byte e; 0 for e = 0 (black). */
const SCALES = Float64Array.from({ length: 256 }, (_, e) => (e === 0 ? 0 : 2 ** (e - 136)));

/** rgbe.c's conversion: each channel m * 2^(e - 136); e = 0 is black. */
function writePixel(out: Float32Array, index: number, r: number, g: number, b: number, e: number): void {
  const scale = SCALES[e];
  out[index] = r * scale;
  out[index + 1] = g * scale;
  out[index + 2] = b * scale;
}

export function decodeRgbe(bytes: Uint8Array, checkSize: SizeCheck = checkEnvironmentSize): EnvironmentImage {
  const { width, height, dataStart } = readRgbeHeader(bytes, checkSize);
  const rgb = new Float32Array(width * height * 3);
  const plane = new Uint8Array(width * 4);
  let pos = dataStart;
  for (let y = 0; y < height; y++) {
    const row = y * width * 3;
    if (isRleScanline(bytes, pos, width)) {
      if (((bytes[pos + 2] << 8) | bytes[pos + 3]) !== width) fail('corrupt Radiance file (scanline width differs from the header)');
      pos = readRleScanline(bytes, pos, width, plane);
      for (let x = 0; x < width; x++) {
        writePixel(rgb, row + x * 3, plane[x], plane[width + x], plane[2 * width + x], plane[3 * width + x]);
      }
    } else {
      if (pos + width * 4 > bytes.length) fail('truncated Radiance file (flat scanline data ends early)');
      for (let x = 0; x < width; x++, pos += 4) {
        writePixel(rgb, row + x * 3, bytes[pos], bytes[pos + 1], bytes[pos + 2], bytes[pos + 3]);
      }
    }
  }
  return { width, height, rgb };
}
