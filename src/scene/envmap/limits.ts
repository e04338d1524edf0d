/**
 * Limits of an environment map, checked from the file's header before any
 * pixel is decoded (a 40-byte header must not be able to ask for gigabytes).
 *
 * 8192 x 4096 is WebGL2's texture size on SwiftShader and on nearly every
 * desktop GPU (MAX_TEXTURE_SIZE >= 8192); WebGL2 itself only promises 2048,
 * so the upload (src/render/environmentTextures.ts) checks the real limit
 * again. Memory: a map at the limit takes 400 MB as RGB float32 on the CPU
 * and 512 MB as an RGBA32F texture; 4096 x 2048 (the common "4k" map) a
 * quarter of that.
 */
export const MAX_ENVIRONMENT_WIDTH = 8192;
export const MAX_ENVIRONMENT_HEIGHT = 4096;

/** Checks a file's size from its header; throws through `fail`. The texture decoders (src/scene/texture/) pass their own limits. */
export type SizeCheck = (width: number, height: number, fail: (message: string) => never) => void;

/** Throws unless width x height lies within the limits (shared by the decoders). */
export function checkEnvironmentSize(width: number, height: number, fail: (message: string) => never): void {
  if (!Number.isInteger(width) || !Number.isInteger(height) || width < 1 || height < 1) {
    fail(`image size ${width}x${height} is not a positive size`);
  }
  if (width > MAX_ENVIRONMENT_WIDTH || height > MAX_ENVIRONMENT_HEIGHT) {
    fail(`image is ${width}x${height}, larger than the maximum ${MAX_ENVIRONMENT_WIDTH}x${MAX_ENVIRONMENT_HEIGHT}`);
  }
}
