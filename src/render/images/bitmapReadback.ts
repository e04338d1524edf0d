/**
 * The browser's JPEG/WebP decoder for src/scene/texture/decode.ts, in a
 * Worker: createImageBitmap without premultiplying alpha or converting
 * colour spaces (the format asks for the file's own values), then the
 * bitmap's texels read back.
 *
 * The read-back goes through WebGL2 (a texture upload with
 * UNPACK_PREMULTIPLY_ALPHA_WEBGL false, then readPixels from a framebuffer),
 * which is exact: test/browser/texture-decode.test.ts measures it against a
 * lossless WebP whose texels have every alpha. OffscreenCanvas 2D's
 * getImageData is not: Chrome keeps a 2D canvas premultiplied, so a texel of
 * alpha a < 255 comes back rounded to a multiple of about 255 / a (exact only
 * where the image is opaque). The 2D path remains for a Worker without
 * WebGL2.
 */
import { AssetError } from '../../scene/assetError';
import type { BitmapDecoder } from '../../scene/texture/image';

export type Readback = 'webgl' | '2d';

export interface DecodedBitmap {
  width: number;
  height: number;
  data: Uint8Array;
}

let gl: WebGL2RenderingContext | null | undefined;

function readbackContext(): WebGL2RenderingContext | null {
  if (gl === undefined) {
    try {
      gl = new OffscreenCanvas(1, 1).getContext('webgl2', { premultipliedAlpha: false, antialias: false, depth: false, stencil: false });
    } catch {
      gl = null;
    }
  }
  return gl && !gl.isContextLost() ? gl : null;
}

/** The bitmap's texels, row 0 at the top, through a texture and a framebuffer. */
function readWithWebgl(gl: WebGL2RenderingContext, bitmap: ImageBitmap): DecodedBitmap {
  const { width, height } = bitmap;
  const texture = gl.createTexture();
  const framebuffer = gl.createFramebuffer();
  try {
    gl.bindTexture(gl.TEXTURE_2D, texture);
    gl.pixelStorei(gl.UNPACK_FLIP_Y_WEBGL, false);
    gl.pixelStorei(gl.UNPACK_PREMULTIPLY_ALPHA_WEBGL, false);
    gl.pixelStorei(gl.UNPACK_COLORSPACE_CONVERSION_WEBGL, gl.NONE);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA8, gl.RGBA, gl.UNSIGNED_BYTE, bitmap);
    gl.bindFramebuffer(gl.FRAMEBUFFER, framebuffer);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, texture, 0);
    if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE) throw new Error('the read-back framebuffer is incomplete');
    const data = new Uint8Array(width * height * 4);
    gl.pixelStorei(gl.PACK_ALIGNMENT, 1);
    // Framebuffer row 0 is texture row 0, the image's top row (no flip on upload).
    gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, data);
    const error = gl.getError();
    if (error !== gl.NO_ERROR) throw new Error(`WebGL error 0x${error.toString(16)} reading the image back (${width}x${height}: larger than this GPU's textures?)`);
    return { width, height, data };
  } finally {
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.deleteFramebuffer(framebuffer);
    gl.deleteTexture(texture);
  }
}

/** Through a 2D canvas: exact for opaque texels only (see above). */
function readWith2d(bitmap: ImageBitmap): DecodedBitmap {
  const { width, height } = bitmap;
  const context = new OffscreenCanvas(width, height).getContext('2d', { willReadFrequently: true });
  if (!context) throw new Error('no 2D canvas to read the image back');
  context.drawImage(bitmap, 0, 0);
  const pixels = context.getImageData(0, 0, width, height);
  return { width, height, data: new Uint8Array(pixels.data.buffer, pixels.data.byteOffset, pixels.data.byteLength) };
}

/** A BitmapDecoder; `readback` '2d' only for the test that measures it. */
export function bitmapDecoder(readback: Readback = 'webgl'): BitmapDecoder {
  return async (bytes, mime) => {
    // A failure here is the file's (decodeTextureImage calls it corrupt); one after it is the read-back's.
    const bitmap = await createImageBitmap(new Blob([bytes as Uint8Array<ArrayBuffer>], { type: mime }), { premultiplyAlpha: 'none', colorSpaceConversion: 'none' });
    try {
      const context = readback === 'webgl' ? readbackContext() : null;
      return context ? readWithWebgl(context, bitmap) : readWith2d(bitmap);
    } catch (error) {
      throw new AssetError(`the browser decoded this ${bitmap.width}x${bitmap.height} image but could not read its texels back (${(error as Error)?.message ?? String(error)})`);
    } finally {
      bitmap.close();
    }
  };
}
