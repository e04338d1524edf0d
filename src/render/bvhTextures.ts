/**
 * The packed BVH (src/render/bvh/pack.ts) as one RGBA32F 2D array texture for
 * src/shaders/scene/bvh.glsl: `uBvh`. Upload once per scene; bind to a
 * texture unit before each draw with a program that includes bvh.glsl
 * (compiled with `bvhDefines()`).
 */
import type { Program } from './gl/program';
import { createDataTextureArray } from './gl/dataTexture';
import { BVH_CODE_BIAS, BVH_FIRST_SLOT, BVH_LAYER_ROWS, BVH_ROOT_NODE, BVH_ROW_TRIANGLES, BVH_TEXTURE_WIDTH, type PackedBvh } from './bvh/pack';
import { MAX_WIDE_STACK } from './bvh/wide';

/** The #defines bvh.glsl expects (its defaults equal these; pass them to keep TS and GLSL in one place). */
export function bvhDefines(): Record<string, number> {
  return {
    BVH_TEXTURE_WIDTH_LOG2: Math.log2(BVH_TEXTURE_WIDTH),
    BVH_LAYER_ROWS_LOG2: Math.log2(BVH_LAYER_ROWS),
    BVH_STACK_SIZE: MAX_WIDE_STACK,
    BVH_ROW_TRIANGLES,
    BVH_ROOT_NODE,
    BVH_FIRST_SLOT,
    BVH_CODE_BIAS,
  };
}

export class BvhTextures {
  readonly texture: WebGLTexture;

  constructor(
    private readonly gl: WebGL2RenderingContext,
    packed: PackedBvh,
  ) {
    const { width, height, layers, data } = packed.texture;
    this.texture = createDataTextureArray(gl, width, height, layers, data);
  }

  /** Binds the texture to the given unit and points the program's sampler at it (the program must be in use). */
  bind(program: Program, unit: number): void {
    const gl = this.gl;
    gl.activeTexture(gl.TEXTURE0 + unit);
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, this.texture);
    // The sampler uniform takes a unit number, as sampler2D's do.
    program.setUniforms({ uBvh: unit }, { uBvh: 'int' });
  }

  dispose(): void {
    this.gl.deleteTexture(this.texture);
  }
}
