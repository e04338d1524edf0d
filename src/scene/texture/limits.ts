/**
 * Limits of texture images (scene format version 3, "Textures"), checked
 * from a file's header before any texel is decoded: a few bytes of header
 * must not be able to ask for gigabytes.
 *
 * 8192 is WebGL2's MAX_TEXTURE_SIZE on SwiftShader and on nearly every
 * desktop GPU; the upload halves an image that a device cannot hold.
 */
export const MAX_TEXTURE_SIDE = 8192;

/**
 * The decoded images of one scene, together, at most (the scene's loader
 * checks the total). One image larger than this alone is refused by the
 * decoder before decoding: an 8192 x 8192 float image would take 1 GB.
 */
export const MAX_TEXTURE_BYTES = 512 * 2 ** 20;

/** Throws through `fail` unless width x height is a positive size within MAX_TEXTURE_SIDE. */
export function checkTextureSize(width: number, height: number, fail: (message: string) => never): void {
  if (!Number.isInteger(width) || !Number.isInteger(height) || width < 1 || height < 1) {
    fail(`image size ${width}x${height} is not a positive size`);
  }
  if (width > MAX_TEXTURE_SIDE || height > MAX_TEXTURE_SIDE) {
    fail(`image is ${width}x${height}, larger than the maximum ${MAX_TEXTURE_SIDE} texels on a side`);
  }
}
