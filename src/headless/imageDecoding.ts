/**
 * Test hook of the texture image Worker (src/render/images/decodeImages.ts)
 * for test/browser/texture-decode.test.ts and the timings in its report:
 * registers `window.pathtraceImages` on the headless page.
 */
import { decodeImageOffThread, type ImageTimings } from '../render/images/decodeImages';
import type { Readback } from '../render/images/bitmapReadback';

export interface DecodedForTest {
  width: number;
  height: number;
  format: string;
  encoding: string;
  /** The texels' bytes, base64. */
  data: string;
  timings: ImageTimings;
}

function fromBase64(text: string): Uint8Array<ArrayBuffer> {
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
  return bytes;
}

function toBase64(view: ArrayBufferView): string {
  const bytes = new Uint8Array(view.buffer, view.byteOffset, view.byteLength);
  let text = '';
  for (let i = 0; i < bytes.length; i += 0x8000) text += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(text);
}

const api = {
  /** Decodes base64 file bytes in the Worker; an error comes back as `{ error: 'Name: message' }`. */
  async decode(file: string, readback?: Readback): Promise<DecodedForTest | { error: string }> {
    try {
      const image = await decodeImageOffThread(fromBase64(file), readback);
      const timings = (globalThis as unknown as { __imageTimings: ImageTimings }).__imageTimings;
      return { width: image.width, height: image.height, format: image.format, encoding: image.encoding, data: toBase64(image.data), timings };
    } catch (error) {
      return { error: `${(error as Error).name}: ${(error as Error).message}` };
    }
  },
  /** Encodes RGBA8 texels (base64) with the browser's encoder (`image/jpeg`, `image/webp`), for the timings. */
  async encode(rgba: string, width: number, height: number, type: string, quality: number): Promise<string> {
    const canvas = new OffscreenCanvas(width, height);
    const context = canvas.getContext('2d');
    if (!context) throw new Error('no 2D canvas');
    context.putImageData(new ImageData(new Uint8ClampedArray(fromBase64(rgba).buffer), width, height), 0, 0);
    const blob = await canvas.convertToBlob({ type, quality });
    return toBase64(new Uint8Array(await blob.arrayBuffer()));
  },
};

declare global {
  interface Window {
    pathtraceImages: typeof api;
  }
}

window.pathtraceImages = api;
