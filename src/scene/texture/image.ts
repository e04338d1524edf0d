/**
 * A decoded texture image, as every decoder of src/scene/texture/ returns it
 * and the renderer uploads it.
 */

/** How the texel values are stored: 8-bit (colour inputs decode them from sRGB), 16-bit PNG (likewise sRGB for colour inputs), linear float (EXR/HDR). */
export type TexelEncoding = 'u8' | 'u16' | 'f32';

export type ImageFormat = 'png' | 'jpeg' | 'webp' | 'exr' | 'hdr';

/** A decoded texture image: RGBA, 4 values per texel, row 0 the image's top row, alpha not premultiplied. */
export interface TextureImage {
  width: number;
  height: number;
  format: ImageFormat;
  encoding: TexelEncoding;
  data: Uint8Array | Uint16Array | Float32Array; // u8 / u16 / f32
}

/**
 * Decodes JPEG/WebP (the browser's own decoder); absent in Node. Returns
 * RGBA8 unpremultiplied, row 0 at the top, as the browser shows the image
 * (a JPEG's EXIF orientation applied, as createImageBitmap always does:
 * decodeTextureImage undoes it).
 */
export type BitmapDecoder = (bytes: Uint8Array, mime: string) => Promise<{ width: number; height: number; data: Uint8Array }>;

/** Bytes per texel of each encoding (4 channels). */
export const TEXEL_BYTES: Record<TexelEncoding, number> = { u8: 4, u16: 8, f32: 16 };

/** The bytes an image takes decoded (what MAX_TEXTURE_BYTES counts). */
export function textureImageBytes(image: { width: number; height: number; encoding: TexelEncoding }): number {
  return image.width * image.height * TEXEL_BYTES[image.encoding];
}
