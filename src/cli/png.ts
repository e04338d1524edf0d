/** 8-bit RGBA PNG encoding and decoding through pngjs (rows top to bottom, as PNG stores them). */
import { PNG } from 'pngjs';

export interface PngImage {
  width: number;
  height: number;
  /** RGBA8, rows top to bottom, width * height * 4 bytes. */
  rgba: Uint8Array;
}

/** Encodes RGBA8 pixels as a PNG (colour type 6, 8 bits). Deterministic: same pixels, same bytes. */
export function encodePng(width: number, height: number, rgba: Uint8Array): Buffer {
  if (!Number.isInteger(width) || !Number.isInteger(height) || width < 1 || height < 1) {
    throw new RangeError(`bad image size ${width}x${height}`);
  }
  if (rgba.length !== width * height * 4) {
    throw new RangeError(`encodePng: expected ${width * height * 4} RGBA bytes, got ${rgba.length}`);
  }
  const png = new PNG({ width, height, colorType: 6, inputColorType: 6, bitDepth: 8, inputHasAlpha: true });
  png.data = Buffer.from(rgba.buffer, rgba.byteOffset, rgba.byteLength);
  return PNG.sync.write(png, { colorType: 6, inputColorType: 6, inputHasAlpha: true });
}

/** Decodes any PNG pngjs understands into RGBA8 rows top to bottom. */
export function decodePng(data: Uint8Array): PngImage {
  const png = PNG.sync.read(Buffer.from(data.buffer, data.byteOffset, data.byteLength));
  return { width: png.width, height: png.height, rgba: new Uint8Array(png.data.buffer, png.data.byteOffset, png.data.byteLength) };
}
