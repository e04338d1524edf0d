/**
 * Data textures: float or unsigned-integer textures the shaders read with
 * texelFetch only (32-bit float and integer textures are not filterable in
 * WebGL2, so every one is NEAREST), one texel per entry.
 */

/** The texel formats a data texture can have. */
export type DataTextureFormat = 'rgba32f' | 'rgb32f' | 'rgba32ui';

function formats(gl: WebGL2RenderingContext, format: DataTextureFormat): { internalFormat: number; format: number; type: number } {
  switch (format) {
    case 'rgba32f':
      return { internalFormat: gl.RGBA32F, format: gl.RGBA, type: gl.FLOAT };
    case 'rgb32f':
      return { internalFormat: gl.RGB32F, format: gl.RGB, type: gl.FLOAT };
    case 'rgba32ui':
      return { internalFormat: gl.RGBA32UI, format: gl.RGBA_INTEGER, type: gl.UNSIGNED_INT };
  }
}

function setNearest(gl: WebGL2RenderingContext, target: number): void {
  gl.texParameteri(target, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
  gl.texParameteri(target, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
}

/**
 * A `width` x `height` 2D data texture, NEAREST, with `data` uploaded when
 * given (else left for texSubImage2D, e.g. uploadDataTexture). Leaves it
 * bound to TEXTURE_2D of the active unit.
 */
export function createDataTexture(
  gl: WebGL2RenderingContext,
  width: number,
  height: number,
  data: Float32Array | Uint32Array | null = null,
  format: DataTextureFormat = 'rgba32f',
): WebGLTexture {
  const f = formats(gl, format);
  const texture = gl.createTexture()!;
  gl.bindTexture(gl.TEXTURE_2D, texture);
  gl.texStorage2D(gl.TEXTURE_2D, 1, f.internalFormat, width, height);
  if (data) {
    // Rows of 12 or 16 bytes a texel: already 4-byte aligned.
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 4);
    gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, width, height, f.format, f.type, data);
  }
  setNearest(gl, gl.TEXTURE_2D);
  return texture;
}

/** Writes `data` into the first `width` x `height` texels of a 2D data texture (leaves it bound to TEXTURE_2D). */
export function uploadDataTexture(
  gl: WebGL2RenderingContext,
  texture: WebGLTexture,
  width: number,
  height: number,
  data: Float32Array | Uint32Array,
  format: DataTextureFormat = 'rgba32f',
): void {
  const f = formats(gl, format);
  gl.bindTexture(gl.TEXTURE_2D, texture);
  gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, width, height, f.format, f.type, data);
}

/** A `width` x `height` x `layers` 2D array data texture, NEAREST, with `data` uploaded. Leaves it bound to TEXTURE_2D_ARRAY. */
export function createDataTextureArray(
  gl: WebGL2RenderingContext,
  width: number,
  height: number,
  layers: number,
  data: Float32Array | Uint32Array,
  format: DataTextureFormat = 'rgba32f',
): WebGLTexture {
  const f = formats(gl, format);
  const texture = gl.createTexture()!;
  gl.bindTexture(gl.TEXTURE_2D_ARRAY, texture);
  gl.texStorage3D(gl.TEXTURE_2D_ARRAY, 1, f.internalFormat, width, height, layers);
  gl.pixelStorei(gl.UNPACK_ALIGNMENT, 4);
  gl.texSubImage3D(gl.TEXTURE_2D_ARRAY, 0, 0, 0, 0, width, height, layers, f.format, f.type, data);
  setNearest(gl, gl.TEXTURE_2D_ARRAY);
  return texture;
}
