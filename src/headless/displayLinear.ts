/**
 * Tone-maps a linear RGBA image handed to the page (the denoised one)
 * through the same display pass the tracer uses (exposure, tone map, exact
 * sRGB), so a denoised PNG is displayed exactly like a plain one.
 */
import { createContext } from '../render/gl/context';
import { flipRows } from '../render/gl/rows';
import { FloatTarget } from '../render/gl/targets';
import { DisplayPass, type DisplayOptions } from '../render/passes/display';

/** linear: RGBA float32, rows top to bottom. Returns RGBA8 sRGB, rows top to bottom. */
export function displayLinear(linear: Float32Array, width: number, height: number, options: DisplayOptions): Uint8Array {
  if (linear.length !== width * height * 4) throw new Error(`displayLinear: expected ${width * height * 4} values, got ${linear.length}`);
  const canvas = new OffscreenCanvas(width, height);
  const gl = createContext(canvas, false);
  const source = new FloatTarget(gl, width, height);
  const display = new DisplayPass(gl);
  try {
    gl.bindTexture(gl.TEXTURE_2D, source.texture);
    // GL rows run bottom to top.
    gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, width, height, gl.RGBA, gl.FLOAT, flipRows(linear, width, height, 4));
    return display.read(source, 1, options, width, height);
  } finally {
    display.dispose();
    source.dispose();
    gl.getExtension('WEBGL_lose_context')?.loseContext();
  }
}
