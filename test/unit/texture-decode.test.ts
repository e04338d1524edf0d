/**
 * Texture image decoding (src/scene/texture/): every PNG layout to RGBA at
 * the file's precision, the float formats through the environment maps'
 * decoders, and the refusals (corrupt, truncated, oversized, KTX2, JPEG/WebP
 * without a browser) as AssetError. The test PNGs are written here, byte by
 * byte (node:zlib), so the decoder is checked against the PNG specification
 * rather than against an encoder from the same library.
 */
import { readFileSync } from 'node:fs';
import { crc32, deflateSync } from 'node:zlib';
import fc from 'fast-check';
import { PNG } from 'pngjs';
import { afterAll, beforeAll, describe, expect, it, vi } from 'vitest';
import { AssetError } from '../../src/scene/assetError';
import { decodeEnvironmentMap } from '../../src/scene/envmap/decode';
import { decodeTextureImage } from '../../src/scene/texture/decode';
import { imageHeader } from '../../src/scene/texture/header';
import { MAX_TEXTURE_SIDE } from '../../src/scene/texture/limits';
import type { BitmapDecoder } from '../../src/scene/texture/image';

const ENVMAPS = new URL('../fixtures/envmaps/', import.meta.url);

function chunk(type: string, data: Uint8Array): Buffer {
  const body = Buffer.concat([Buffer.from(type, 'latin1'), data]);
  const length = Buffer.alloc(4);
  length.writeUInt32BE(data.length);
  const crc = Buffer.alloc(4);
  crc.writeUInt32BE(crc32(body));
  return Buffer.concat([length, body, crc]);
}

interface PngSpec {
  width: number;
  height: number;
  colorType: number;
  depth: number;
  /** The unfiltered scanlines, each already packed (filter byte 0 is added here). */
  rows: Uint8Array[];
  /** Chunks before IDAT (PLTE, tRNS). */
  extra?: Buffer[];
  interlace?: number;
}

/** A PNG built from its specification: signature, IHDR, extra chunks, one IDAT, IEND. */
function makePng({ width, height, colorType, depth, rows, extra = [], interlace = 0 }: PngSpec): Uint8Array {
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(width, 0);
  ihdr.writeUInt32BE(height, 4);
  ihdr.set([depth, colorType, 0, 0, interlace], 8);
  const raw = Buffer.concat(rows.flatMap((row) => [Buffer.from([0]), Buffer.from(row)]));
  const png = Buffer.concat([
    Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]),
    chunk('IHDR', ihdr),
    ...extra,
    chunk('IDAT', deflateSync(raw)),
    chunk('IEND', new Uint8Array(0)),
  ]);
  return new Uint8Array(png);
}

/** The scanlines of Adam7's seven passes (PNG specification, 8.2), each pass a sub-image of every (dx, dy)-th texel from (x0, y0). */
function adam7Rows(rows: Uint8Array[], width: number, height: number, bytesPerTexel: number): Uint8Array[] {
  const passes = [[0, 0, 8, 8], [4, 0, 8, 8], [0, 4, 4, 8], [2, 0, 4, 4], [0, 2, 2, 4], [1, 0, 2, 2], [0, 1, 1, 2]];
  const out: Uint8Array[] = [];
  for (const [x0, y0, dx, dy] of passes) {
    if (x0 >= width) continue;
    for (let y = y0; y < height; y += dy) {
      const texels: number[] = [];
      for (let x = x0; x < width; x += dx) texels.push(...rows[y].subarray(x * bytesPerTexel, (x + 1) * bytesPerTexel));
      out.push(Uint8Array.from(texels));
    }
  }
  return out;
}

/** 16-bit samples as PNG stores them (big-endian). */
function be16(values: number[]): Uint8Array {
  const out = new Uint8Array(values.length * 2);
  values.forEach((v, i) => out.set([v >> 8, v & 0xff], i * 2));
  return out;
}

/** An 8 x 8 RGBA 8-bit PNG of varied texels. */
function good(): Uint8Array {
  return makePng({ width: 8, height: 8, colorType: 6, depth: 8, rows: Array.from({ length: 8 }, (_, y) => Uint8Array.from({ length: 32 }, (_, i) => (i * 7 + y * 31) & 0xff)) });
}

async function assetError(promise: Promise<unknown>): Promise<string> {
  try {
    await promise;
  } catch (error) {
    expect(error, String(error)).toBeInstanceOf(AssetError);
    return (error as Error).message;
  }
  throw new Error('expected an AssetError, the image decoded');
}

function syncAssetError(run: () => unknown): string {
  try {
    run();
  } catch (error) {
    expect(error, String(error)).toBeInstanceOf(AssetError);
    return (error as Error).message;
  }
  throw new Error('expected an AssetError');
}

describe('PNG texture images', () => {
  it('RGBA 8-bit (written by pngjs) decodes to its exact values, top row first', async () => {
    const png = new PNG({ width: 3, height: 2 });
    for (let i = 0; i < png.data.length; i++) png.data[i] = (i * 53 + 7) & 0xff;
    const bytes = new Uint8Array(PNG.sync.write(png, { colorType: 6 }));
    const image = await decodeTextureImage(bytes);
    expect(image).toMatchObject({ width: 3, height: 2, format: 'png', encoding: 'u8' });
    expect(image.data).toBeInstanceOf(Uint8Array);
    expect(Array.from(image.data)).toEqual(Array.from(png.data));
  });

  it('RGB 8-bit: alpha 255; a tRNS colour key gives alpha 0 on that colour only', async () => {
    const rows = [Uint8Array.of(10, 20, 30, 40, 50, 60), Uint8Array.of(255, 0, 128, 10, 20, 30)];
    const plain = await decodeTextureImage(makePng({ width: 2, height: 2, colorType: 2, depth: 8, rows }));
    expect(Array.from(plain.data)).toEqual([10, 20, 30, 255, 40, 50, 60, 255, 255, 0, 128, 255, 10, 20, 30, 255]);
    const keyed = await decodeTextureImage(makePng({ width: 2, height: 2, colorType: 2, depth: 8, rows, extra: [chunk('tRNS', be16([10, 20, 30]))] }));
    expect(Array.from(keyed.data)).toEqual([10, 20, 30, 0, 40, 50, 60, 255, 255, 0, 128, 255, 10, 20, 30, 0]);
  });

  it('grey 8-bit and grey+alpha 8-bit (pngjs) spread grey to RGB', async () => {
    const grey = await decodeTextureImage(makePng({ width: 3, height: 1, colorType: 0, depth: 8, rows: [Uint8Array.of(0, 77, 255)] }));
    expect(Array.from(grey.data)).toEqual([0, 0, 0, 255, 77, 77, 77, 255, 255, 255, 255, 255]);
    const png = new PNG({ width: 2, height: 1, colorType: 4 });
    png.data.set([200, 200, 200, 17, 33, 33, 33, 250]);
    const ga = await decodeTextureImage(new Uint8Array(PNG.sync.write(png, { colorType: 4, inputColorType: 6 })));
    expect(Array.from(ga.data)).toEqual([200, 200, 200, 17, 33, 33, 33, 250]);
  });

  it('grey of 1, 2 and 4 bits is scaled exactly to 8 bits (v * 255 / (2^depth - 1))', async () => {
    // 1 bit: 1 0 1 (+ 5 padding bits); 2 bits: 3 2 1 0 1; 4 bits: 15 0 7.
    const one = await decodeTextureImage(makePng({ width: 3, height: 1, colorType: 0, depth: 1, rows: [Uint8Array.of(0b10100000)] }));
    expect(Array.from(one.data).filter((_, i) => i % 4 === 0)).toEqual([255, 0, 255]);
    const two = await decodeTextureImage(makePng({ width: 5, height: 1, colorType: 0, depth: 2, rows: [Uint8Array.of(0b11100100, 0b01000000)] }));
    expect(Array.from(two.data).filter((_, i) => i % 4 === 0)).toEqual([255, 170, 85, 0, 85]);
    const four = await decodeTextureImage(makePng({ width: 3, height: 2, colorType: 0, depth: 4, rows: [Uint8Array.of(0xf0, 0x70), Uint8Array.of(0x12, 0x30)] }));
    expect(Array.from(four.data).filter((_, i) => i % 4 === 0)).toEqual([255, 0, 119, 17, 34, 51]);
  });

  it('palette (8 and 2 bits an index) with tRNS: RGBA of the entries, alpha 255 past the tRNS list', async () => {
    const plte = chunk('PLTE', Uint8Array.of(255, 0, 0, 0, 255, 0, 0, 0, 255, 9, 8, 7));
    const trns = chunk('tRNS', Uint8Array.of(0, 128));
    const eight = await decodeTextureImage(makePng({ width: 4, height: 1, colorType: 3, depth: 8, rows: [Uint8Array.of(3, 2, 1, 0)], extra: [plte, trns] }));
    expect(Array.from(eight.data)).toEqual([9, 8, 7, 255, 0, 0, 255, 255, 0, 255, 0, 128, 255, 0, 0, 0]);
    const two = await decodeTextureImage(makePng({ width: 3, height: 2, colorType: 3, depth: 2, rows: [Uint8Array.of(0b00011100), Uint8Array.of(0b11000000)], extra: [plte] }));
    expect(two.encoding).toBe('u8');
    expect(Array.from(two.data)).toEqual([255, 0, 0, 255, 0, 255, 0, 255, 9, 8, 7, 255, 9, 8, 7, 255, 255, 0, 0, 255, 255, 0, 0, 255]);
  });

  it('a palette index beyond the palette is an AssetError', async () => {
    const plte = chunk('PLTE', Uint8Array.of(1, 2, 3));
    const message = await assetError(decodeTextureImage(makePng({ width: 2, height: 1, colorType: 3, depth: 8, rows: [Uint8Array.of(0, 5)], extra: [plte] })));
    expect(message).toMatch(/palette index 5 beyond the palette's 1 colours/);
  });

  it('16-bit RGBA, RGB and grey keep all 16 bits (Uint16Array)', async () => {
    const rgba = [0, 1, 0x1234, 0xffff, 0xfffe, 0x8000, 0x00ff, 0x7fff];
    const a = await decodeTextureImage(makePng({ width: 2, height: 1, colorType: 6, depth: 16, rows: [be16(rgba)] }));
    expect(a).toMatchObject({ width: 2, height: 1, encoding: 'u16' });
    expect(a.data).toBeInstanceOf(Uint16Array);
    expect(Array.from(a.data)).toEqual(rgba);
    const b = await decodeTextureImage(makePng({ width: 1, height: 2, colorType: 2, depth: 16, rows: [be16([1, 2, 65535]), be16([40000, 300, 7])] }));
    expect(Array.from(b.data)).toEqual([1, 2, 65535, 65535, 40000, 300, 7, 65535]);
    const g = await decodeTextureImage(makePng({ width: 2, height: 1, colorType: 4, depth: 16, rows: [be16([513, 1000, 65535, 2])] }));
    expect(Array.from(g.data)).toEqual([513, 513, 513, 1000, 65535, 65535, 65535, 2]);
  });

  it('an interlaced (Adam7) PNG decodes like the plain one (8-bit RGBA, 16-bit grey)', async () => {
    for (const [colorType, depth, bytesPerTexel] of [[6, 8, 4], [0, 16, 2]]) {
      const width = 11;
      const height = 9;
      const texels = Array.from({ length: height }, (_, y) => Uint8Array.from({ length: width * bytesPerTexel }, (_, i) => (i * 29 + y * 71 + 5) & 0xff));
      const plain = await decodeTextureImage(makePng({ width, height, colorType, depth, rows: texels }));
      const laced = await decodeTextureImage(makePng({ width, height, colorType, depth, rows: adam7Rows(texels, width, height, bytesPerTexel), interlace: 1 }));
      expect(Array.from(laced.data), `colour type ${colorType}, ${depth} bits`).toEqual(Array.from(plain.data));
    }
    const message = await assetError(decodeTextureImage(makePng({ width: 1, height: 1, colorType: 0, depth: 1, rows: [Uint8Array.of(0x80)], interlace: 1 })));
    expect(message).toMatch(/interlaced PNG files with 1 bits a channel are not supported/);
  });

  it('a truncated PNG is an AssetError (at every cut past the header)', async () => {
    const bytes = good();
    for (let cut = 33; cut < bytes.length; cut += 3) {
      expect(await assetError(decodeTextureImage(bytes.subarray(0, cut))), `cut at ${cut}`).toMatch(/^corrupt or truncated PNG file/);
    }
    expect(await assetError(decodeTextureImage(bytes.subarray(0, 20)))).toBe('truncated PNG file (no complete IHDR header)');
  });

  it('a corrupt PNG (a byte flipped anywhere inside IDAT, or a wrong CRC) is an AssetError', async () => {
    const bytes = good();
    const type = Buffer.from(bytes).indexOf('IDAT');
    const length = new DataView(bytes.buffer).getUint32(type - 4);
    for (let at = type + 4; at < type + 4 + length; at++) {
      const corrupt = bytes.slice();
      corrupt[at] ^= 0x10;
      // zlib notices some flips first (bad distance, bad block type), the chunk's CRC the others.
      expect(await assetError(decodeTextureImage(corrupt)), `byte ${at}`).toMatch(/^corrupt or truncated PNG file \((Error while decompressing the data: |CRC mismatch)/);
    }
    const badCrc = bytes.slice();
    badCrc[type + 4 + length] ^= 1;
    expect(await assetError(decodeTextureImage(badCrc))).toMatch(/^corrupt or truncated PNG file \(CRC mismatch for chunk IDAT/);
  });

  it('an IHDR claiming 100000 x 100000 is refused by imageHeader, before anything is allocated', async () => {
    const huge = makePng({ width: 1, height: 1, colorType: 6, depth: 8, rows: [Uint8Array.of(0, 0, 0, 0)] });
    const view = new DataView(huge.buffer);
    view.setUint32(16, 100000);
    view.setUint32(20, 100000);
    // Only the 33 bytes of signature and IHDR: there are no texels to decode, so a refusal here is the header's.
    expect(syncAssetError(() => imageHeader(huge.subarray(0, 33)))).toBe(`image is 100000x100000, larger than the maximum ${MAX_TEXTURE_SIDE} texels on a side`);
    expect(await assetError(decodeTextureImage(huge))).toBe(`image is 100000x100000, larger than the maximum ${MAX_TEXTURE_SIDE} texels on a side`);
    view.setUint32(16, MAX_TEXTURE_SIDE);
    view.setUint32(20, MAX_TEXTURE_SIDE + 1);
    expect(syncAssetError(() => imageHeader(huge))).toMatch(/8192x8193, larger than the maximum/);
    view.setUint32(20, 0);
    expect(syncAssetError(() => imageHeader(huge))).toMatch(/not a positive size/);
  });
});

describe('image headers', () => {
  it('tells the formats apart by their signatures and reads their sizes', () => {
    expect(imageHeader(good8x8())).toEqual({ format: 'png', width: 8, height: 8 });
    expect(imageHeader(new Uint8Array(readFileSync(new URL('gradient-rle.hdr', ENVMAPS))))).toMatchObject({ format: 'hdr' });
    expect(imageHeader(new Uint8Array(readFileSync(new URL('gradient-half-zip.exr', ENVMAPS))))).toMatchObject({ format: 'exr' });
    expect(imageHeader(jpegHeader(640, 480))).toEqual({ format: 'jpeg', width: 640, height: 480 });
    expect(imageHeader(webpVp8lHeader(5000, 3))).toEqual({ format: 'webp', width: 5000, height: 3 });
    expect(syncAssetError(() => imageHeader(webpVp8lHeader(9000, 3)))).toMatch(/9000x3, larger than the maximum/);
  });

  it('KTX2 is refused naming KTX2/Basis; other formats and junk get a clear message', () => {
    const ktx2 = Uint8Array.of(0xab, 0x4b, 0x54, 0x58, 0x20, 0x32, 0x30, 0xbb, 0x0d, 0x0a, 0x1a, 0x0a, 0, 0, 0, 0);
    expect(syncAssetError(() => imageHeader(ktx2))).toMatch(/^KTX2\/Basis images are not supported: /);
    expect(syncAssetError(() => imageHeader(new TextEncoder().encode('GIF89a....')))).toMatch(/^GIF images are not supported/);
    expect(syncAssetError(() => imageHeader(new TextEncoder().encode('hello, world')))).toBe('not a PNG, JPEG, WebP, OpenEXR or Radiance .hdr image (its first bytes match none of them)');
    expect(syncAssetError(() => imageHeader(new Uint8Array(0)))).toBe('the file is empty');
    expect(syncAssetError(() => imageHeader(jpegHeader(640, 480).subarray(0, 12)))).toMatch(/^truncated JPEG file/);
  });
});

/** SOI, an APP0 segment, SOF0 with the size (no image data: enough for the header). */
function jpegHeader(width: number, height: number): Uint8Array {
  return Uint8Array.of(0xff, 0xd8, 0xff, 0xe0, 0, 4, 0, 0, 0xff, 0xc0, 0, 11, 8, height >> 8, height & 0xff, width >> 8, width & 0xff, 1, 1, 0x11, 0);
}

/** RIFF/WEBP with a VP8L chunk's 5-byte header: 0x2f, then 14 bits width - 1, 14 bits height - 1. */
function webpVp8lHeader(width: number, height: number): Uint8Array {
  const bits = (width - 1) | ((height - 1) << 14);
  return Uint8Array.of(...new TextEncoder().encode('RIFF'), 0, 0, 0, 0, ...new TextEncoder().encode('WEBPVP8L'), 5, 0, 0, 0, 0x2f, bits & 0xff, (bits >> 8) & 0xff, (bits >> 16) & 0xff, (bits >>> 24) & 0xff);
}

function good8x8(): Uint8Array {
  return makePng({ width: 8, height: 8, colorType: 2, depth: 8, rows: Array.from({ length: 8 }, () => new Uint8Array(24)) });
}

describe('JPEG and WebP', () => {
  it('without a browser decoder they are a clear AssetError', async () => {
    expect(await assetError(decodeTextureImage(jpegHeader(4, 4)))).toMatch(/^JPEG\/WebP images are decoded by the browser/);
    expect(await assetError(decodeTextureImage(webpVp8lHeader(4, 4)))).toMatch(/^JPEG\/WebP images are decoded by the browser/);
  });

  it('go to the bitmap decoder with their MIME type; its failures and wrong sizes become AssetErrors', async () => {
    const calls: string[] = [];
    const bitmap: BitmapDecoder = async (bytes, mime) => {
      calls.push(mime);
      return { width: 4, height: 4, data: new Uint8Array(64).fill(9) };
    };
    const image = await decodeTextureImage(jpegHeader(4, 4), bitmap);
    expect(image).toMatchObject({ width: 4, height: 4, format: 'jpeg', encoding: 'u8' });
    await decodeTextureImage(webpVp8lHeader(4, 4), bitmap);
    expect(calls).toEqual(['image/jpeg', 'image/webp']);
    expect(await assetError(decodeTextureImage(jpegHeader(5, 4), bitmap))).toMatch(/decoded this JPEG image as 4x4, where its header says 5x4/);
    const broken: BitmapDecoder = async () => {
      throw new DOMException('The source image could not be decoded.', 'InvalidStateError');
    };
    expect(await assetError(decodeTextureImage(jpegHeader(4, 4), broken))).toMatch(/^corrupt or truncated JPEG file \(the browser cannot decode it: The source image/);
  });
});

describe('EXIF orientation of JPEGs', () => {
  /** SOI, APP1 Exif (TIFF in either byte order, IFD0: one unrelated tag, then Orientation), then the rest of `jpeg`. */
  function withExif(jpeg: Uint8Array, orientation: number, little: boolean): Uint8Array {
    const u16 = (v: number) => (little ? [v & 0xff, v >> 8] : [v >> 8, v & 0xff]);
    const u32 = (v: number) => (little ? [v & 0xff, (v >> 8) & 0xff, 0, 0] : [0, 0, (v >> 8) & 0xff, v & 0xff]);
    const tiff = [...(little ? [0x49, 0x49] : [0x4d, 0x4d]), ...u16(42), ...u32(8), ...u16(2), ...u16(0x010f), ...u16(2), ...u32(4), 0x41, 0x42, 0x43, 0, ...u16(0x0112), ...u16(3), ...u32(1), ...u16(orientation), 0, 0, ...u32(0)];
    const body = [...new TextEncoder().encode('Exif'), 0, 0, ...tiff];
    return Uint8Array.from([0xff, 0xd8, 0xff, 0xe1, (body.length + 2) >> 8, (body.length + 2) & 0xff, ...body, ...jpeg.subarray(2)]);
  }

  /** The stored 3 x 2 image turned a quarter clockwise (orientation 6), as a browser shows it: 2 x 3. */
  function rotateClockwise(stored: Uint8Array, width: number, height: number): Uint8Array {
    const out = new Uint8Array(stored.length);
    for (let y = 0; y < height; y++) for (let x = 0; x < width; x++) out.set(stored.subarray((y * width + x) * 4, (y * width + x) * 4 + 4), (x * height + (height - 1 - y)) * 4);
    return out;
  }

  it('is read from either byte order, and a browser bitmap turned by it is turned back to the stored texels', async () => {
    const stored = Uint8Array.from({ length: 3 * 2 * 4 }, (_, i) => i * 10);
    const bitmap: BitmapDecoder = async () => ({ width: 2, height: 3, data: rotateClockwise(stored, 3, 2) });
    for (const little of [true, false]) {
      const image = await decodeTextureImage(withExif(jpegHeader(3, 2), 6, little), bitmap);
      expect(image).toMatchObject({ width: 3, height: 2 });
      expect(Array.from(image.data)).toEqual(Array.from(stored));
    }
    // Without the tag the same bitmap has the wrong size for the header.
    expect(await assetError(decodeTextureImage(jpegHeader(3, 2), bitmap))).toMatch(/decoded this JPEG image as 2x3, where its header says 3x2$/);
  });
});

describe('EXR and HDR texture images', () => {
  for (const file of ['gradient-half-zip.exr', 'gradient-float-piz.exr', 'gradient-rle.hdr']) {
    it(`${file} decodes to RGBA float: the environment map decoder's RGB, alpha 1`, async () => {
      const bytes = new Uint8Array(readFileSync(new URL(file, ENVMAPS)));
      const map = decodeEnvironmentMap(bytes, file);
      const image = await decodeTextureImage(bytes);
      expect(image).toMatchObject({ width: map.width, height: map.height, format: file.endsWith('.exr') ? 'exr' : 'hdr', encoding: 'f32' });
      expect(image.data).toBeInstanceOf(Float32Array);
      const rgb = new Float32Array(map.width * map.height * 3);
      for (let p = 0; p < map.width * map.height; p++) {
        rgb.set(image.data.subarray(p * 4, p * 4 + 3), p * 3);
        expect(image.data[p * 4 + 3]).toBe(1);
      }
      expect(rgb).toEqual(map.rgb);
      expect(Math.max(...map.rgb)).toBeGreaterThan(0);
    });
  }

  it('a float image larger than the scene budget alone (8192 x 8192 x 16 bytes) is refused before decoding', async () => {
    const hdr = new TextEncoder().encode('#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X 8192\n');
    expect(await assetError(decodeTextureImage(hdr))).toMatch(/^image is 8192x8192 float RGBA, 1024 MB decoded, more than the 512 MB/);
  });
});

describe('fuzz: bad bytes give AssetError and nothing else', () => {
  // three.js's EXRLoader warns about the unknown attributes that the mutations make.
  beforeAll(() => void vi.spyOn(console, 'warn').mockImplementation(() => {}));
  afterAll(() => vi.restoreAllMocks());
  const seeds = [good(), new Uint8Array(readFileSync(new URL('gradient-rle.hdr', ENVMAPS))), new Uint8Array(readFileSync(new URL('gradient-half-zip.exr', ENVMAPS)))];
  const bitmap: BitmapDecoder = async () => {
    throw new Error('undecodable');
  };
  async function decodeOrAssetError(bytes: Uint8Array): Promise<void> {
    try {
      const image = await decodeTextureImage(bytes, bitmap);
      expect(image.data.length).toBe(image.width * image.height * 4);
    } catch (error) {
      if (!(error instanceof AssetError)) throw new Error(`${(error as Error).name}: ${(error as Error).message}`);
    }
  }

  it('random bytes, and valid files with bytes overwritten or cut short', async () => {
    await fc.assert(fc.asyncProperty(fc.uint8Array({ maxLength: 200 }), (bytes) => decodeOrAssetError(bytes)), { numRuns: 300 });
    const mutation = fc.record({
      seed: fc.integer({ min: 0, max: seeds.length - 1 }),
      edits: fc.array(fc.tuple(fc.nat(), fc.integer({ min: 0, max: 255 })), { maxLength: 8 }),
      cut: fc.option(fc.nat()),
    });
    await fc.assert(
      fc.asyncProperty(mutation, async ({ seed, edits, cut }) => {
        const bytes = seeds[seed].slice();
        for (const [at, value] of edits) bytes[at % bytes.length] = value;
        await decodeOrAssetError(cut === null ? bytes : bytes.subarray(0, cut % bytes.length));
      }),
      { numRuns: 400 },
    );
    // Signatures with random rest: every format's header reader is reached.
    const prefixes = [seeds[0].subarray(0, 16), Uint8Array.of(0xff, 0xd8, 0xff), new TextEncoder().encode('RIFF\0\0\0\0WEBPVP8'), Uint8Array.of(0x76, 0x2f, 0x31, 0x01), new TextEncoder().encode('#?RADIANCE\n')];
    await fc.assert(
      fc.asyncProperty(fc.integer({ min: 0, max: prefixes.length - 1 }), fc.uint8Array({ maxLength: 120 }), (k, rest) => decodeOrAssetError(new Uint8Array([...prefixes[k], ...rest]))),
      { numRuns: 400 },
    );
  });
});
