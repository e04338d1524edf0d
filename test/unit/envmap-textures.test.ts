/**
 * EnvironmentTextures refuses a map or distribution larger than the GPU's
 * MAX_TEXTURE_SIZE before creating any texture (the upload itself is covered
 * by the browser tests, whose kernels go through this class).
 */
import { describe, expect, it } from 'vitest';
import { EnvironmentTextures, EnvironmentTextureSizeError } from '../../src/render/environmentTextures';
import { buildEnvironmentDistribution } from '../../src/scene/envmap/distribution';

/** A WebGL2 context that knows only MAX_TEXTURE_SIZE and fails on any other call. */
function fakeContext(maxTextureSize: number): WebGL2RenderingContext {
  const MAX_TEXTURE_SIZE = 0x0d33;
  return new Proxy({ MAX_TEXTURE_SIZE, getParameter: (p: number) => (p === MAX_TEXTURE_SIZE ? maxTextureSize : null) }, {
    get(target, key) {
      if (key in target) return target[key as keyof typeof target];
      throw new Error(`unexpected WebGL call ${String(key)}`);
    },
  }) as unknown as WebGL2RenderingContext;
}

describe('EnvironmentTextures', () => {
  it('refuses a map wider than MAX_TEXTURE_SIZE before touching the GPU', () => {
    const image = { width: 32, height: 8, rgb: new Float32Array(32 * 8 * 3).fill(1) };
    const distribution = buildEnvironmentDistribution(image);
    expect(() => new EnvironmentTextures(fakeContext(16), image, distribution)).toThrow(EnvironmentTextureSizeError);
    expect(() => new EnvironmentTextures(fakeContext(16), image, distribution)).toThrow(/32x8 texture, but this GPU allows at most 16x16/);
    // Within the limit it goes on to create textures (here: the fake context's first unexpected call).
    expect(() => new EnvironmentTextures(fakeContext(32), image, distribution)).toThrow(/unexpected WebGL call/);
  });
});
