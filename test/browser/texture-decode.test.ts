/**
 * The texture image Worker of the page and the CLI's browser
 * (src/render/images/): PNG decodes there exactly as in Node; JPEG and WebP
 * go through the browser's decoder to the right size and close values; and
 * the read-back of a decoded bitmap keeps texels of alpha < 255 exactly
 * (createImageBitmap with premultiplyAlpha 'none', read through WebGL2),
 * where a 2D canvas would round them (measured here as the reason).
 * Fixtures: test/fixtures/textures/README.md.
 */
import { readFileSync } from 'node:fs';
import { PNG } from 'pngjs';
import { describe, expect, it } from 'vitest';
import { decodeTextureImage } from '../../src/scene/texture/decode';
import { useRenderSession } from '../support/browser';

const TEXTURES = new URL('../fixtures/textures/', import.meta.url);
const file = (name: string) => new Uint8Array(readFileSync(new URL(name, TEXTURES)));
const b64 = (a: Uint8Array) => Buffer.from(a.buffer, a.byteOffset, a.byteLength).toString('base64');
const bytesOf = (text: string) => new Uint8Array(Buffer.from(text, 'base64'));

/** RGBA8 texels of a fixture PNG, read by pngjs (an independent decoder). */
function pngTexels(name: string): Uint8Array {
  const png = PNG.sync.read(Buffer.from(file(name)));
  return new Uint8Array(png.data);
}

describe('texture images in the page\'s Worker', () => {
  const session = useRenderSession();
  const decode = async (bytes: Uint8Array, readback?: 'webgl' | '2d') => {
    const result = await session().page.evaluate(([f, r]) => window.pathtraceImages.decode(f, r), [b64(bytes), readback] as const);
    if ('error' in result) throw new Error(result.error);
    return { ...result, texels: bytesOf(result.data) };
  };

  it('an opaque PNG and one with every alpha decode exactly, as in Node', async () => {
    for (const name of ['smooth.png', 'alpha.png']) {
      const image = await decode(file(name));
      const node = await decodeTextureImage(file(name));
      expect(image).toMatchObject({ width: node.width, height: node.height, format: 'png', encoding: 'u8' });
      expect(Buffer.from(image.texels).equals(Buffer.from(pngTexels(name))), name).toBe(true);
      expect(Buffer.from(image.texels).equals(Buffer.from(node.data.buffer, node.data.byteOffset, node.data.byteLength)), name).toBe(true);
    }
  });

  it('a lossless WebP with every alpha keeps its unpremultiplied texels exactly (WebGL2 read-back); a 2D canvas would not', async () => {
    const expected = pngTexels('alpha.png');
    const image = await decode(file('alpha-lossless.webp'));
    expect(image).toMatchObject({ width: 64, height: 64, format: 'webp', encoding: 'u8' });
    expect(mismatches(image.texels, expected, (i) => true)).toBe(0);
    // The reason for the WebGL2 read-back: through a 2D canvas, colour under alpha < 255 is rounded
    // (premultiplied inside), and lost entirely under alpha 0; opaque texels survive.
    const canvas = await decode(file('alpha-lossless.webp'), '2d');
    const translucent = mismatches(canvas.texels, expected, (i) => expected[i + 3] < 255);
    expect(translucent, 'texels of alpha < 255 that a 2D canvas changes').toBeGreaterThan(1000);
    expect(mismatches(canvas.texels, expected, (i) => expected[i + 3] === 255), 'opaque texels a 2D canvas changes').toBe(0);
  });

  it('a JPEG and a lossy WebP decode to their size and to their reference decoder\'s values', async () => {
    const source = pngTexels('smooth.png');
    for (const [name, reference] of [['smooth.jpg', 'smooth.jpg.djpeg.png'], ['smooth.webp', 'smooth.webp.dwebp.png']]) {
      const image = await decode(file(name));
      expect(image, name).toMatchObject({ width: 48, height: 32, format: name.endsWith('jpg') ? 'jpeg' : 'webp', encoding: 'u8' });
      // Decoders may differ in the last bits (the format says so): against djpeg / dwebp, RGB within 2 levels.
      const { max, alpha } = difference(image.texels, pngTexels(reference));
      expect(max, `${name}: largest difference from ${reference}`).toBeLessThanOrEqual(2);
      expect(alpha, `${name}: alpha`).toBe(0);
      // And the coding error itself is that of quality 95 (the reference decoders are within 10 levels of the source).
      expect(difference(image.texels, source).max, `${name}: largest difference from smooth.png`).toBeLessThanOrEqual(12);
      // Both read-backs agree on an opaque image.
      const canvas = await decode(file(name), '2d');
      expect(Buffer.from(canvas.texels).equals(Buffer.from(image.texels)), `${name}: 2D and WebGL2 read-backs`).toBe(true);
    }
  });

  it('a JPEG with an EXIF orientation decodes as stored (as Mitsuba reads it), whatever the browser shows', async () => {
    const plain = await decode(file('smooth.jpg'));
    for (let orientation = 2; orientation <= 8; orientation++) {
      const image = await decode(withOrientation(file('smooth.jpg'), orientation));
      expect([image.width, image.height], `orientation ${orientation}`).toEqual([48, 32]);
      expect(Buffer.from(image.texels).equals(Buffer.from(plain.texels)), `orientation ${orientation}`).toBe(true);
    }
  });

  it('a corrupt file comes back as the decoder\'s AssetError', async () => {
    const png = file('smooth.png').slice(0, 60);
    await expect(decode(png)).rejects.toThrow(/^AssetError: corrupt or truncated PNG file/);
    const jpeg = file('smooth.jpg');
    const broken = jpeg.slice(0, 200); // the header, then nothing
    await expect(decode(broken)).rejects.toThrow(/^AssetError: corrupt or truncated JPEG file \(the browser cannot decode it/);
    await expect(decode(new TextEncoder().encode('not an image'))).rejects.toThrow(/^AssetError: not a PNG, JPEG, WebP/);
  });
});

/** The JPEG with an APP1 Exif segment (big-endian TIFF, IFD0 holding only Orientation) after SOI. */
function withOrientation(jpeg: Uint8Array, orientation: number): Uint8Array {
  const tiff = [0x4d, 0x4d, 0, 0x2a, 0, 0, 0, 8, 0, 1, 0x01, 0x12, 0, 3, 0, 0, 0, 1, 0, orientation, 0, 0, 0, 0, 0, 0];
  const body = [...Buffer.from('Exif\0\0', 'latin1'), ...tiff];
  return Uint8Array.from([0xff, 0xd8, 0xff, 0xe1, (body.length + 2) >> 8, (body.length + 2) & 0xff, ...body, ...jpeg.subarray(2)]);
}

function mismatches(actual: Uint8Array, expected: Uint8Array, where: (i: number) => boolean): number {
  expect(actual.length).toBe(expected.length);
  let count = 0;
  for (let i = 0; i < expected.length; i += 4) {
    if (!where(i)) continue;
    if (actual[i] !== expected[i] || actual[i + 1] !== expected[i + 1] || actual[i + 2] !== expected[i + 2] || actual[i + 3] !== expected[i + 3]) count++;
  }
  return count;
}

/** Largest RGB difference, and largest alpha difference. */
function difference(actual: Uint8Array, expected: Uint8Array): { max: number; alpha: number } {
  expect(actual.length).toBe(expected.length);
  let max = 0;
  let alpha = 0;
  for (let i = 0; i < expected.length; i++) {
    const d = Math.abs(actual[i] - expected[i]);
    if (i % 4 === 3) alpha = Math.max(alpha, d);
    else max = Math.max(max, d);
  }
  return { max, alpha };
}
