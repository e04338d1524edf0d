/** The display pass: mean radiance -> exposure -> tone map -> sRGB. */
import displayFrag from '../../shaders/display.frag?raw';
import { Program } from '../gl/program';
import { TEXTURE_UNITS } from '../gl/textureUnits';
import { flipRows } from '../gl/rows';
import type { FloatTarget } from '../gl/targets';
import { TONEMAPS, toneMapDefines, type ToneMap } from '../toneMaps';
import { VERTEX_CHUNKS } from '../shaderSources';

export interface DisplayOptions {
  /** Exposure in stops: displayed radiance = mean * 2^exposure. Default 0. */
  exposure?: number;
  /** Tone mapping operator. Default 'none' (clamp). */
  toneMap?: ToneMap;
}

const UNIFORM_TYPES: Record<string, string> = {
  uAccumulation: 'sampler2D',
  uInverseSampleCount: 'float',
  uExposureScale: 'float',
  uToneMap: 'int',
  uViewportSize: 'vec2',
};

export class DisplayPass {
  private readonly program: Program;

  constructor(private readonly gl: WebGL2RenderingContext) {
    this.program = new Program(gl, VERTEX_CHUNKS, [{ name: 'display.frag', source: displayFrag }], toneMapDefines());
  }

  /** Draws into `framebuffer` (null = the canvas) of the given size. */
  draw(
    sums: FloatTarget,
    sampleCount: number,
    options: DisplayOptions,
    framebuffer: WebGLFramebuffer | null,
    width: number,
    height: number,
  ): void {
    const gl = this.gl;
    const toneMap = TONEMAPS.indexOf(options.toneMap ?? 'none');
    if (toneMap < 0) throw new Error(`unknown tone map "${options.toneMap}"; use one of ${TONEMAPS.join(', ')}`);
    this.program.use().setUniforms(
      {
        uAccumulation: TEXTURE_UNITS.accumulation,
        uInverseSampleCount: sampleCount > 0 ? 1 / sampleCount : 0,
        uExposureScale: 2 ** (options.exposure ?? 0),
        uToneMap: toneMap,
        uViewportSize: [width, height],
      },
      UNIFORM_TYPES,
    );
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNITS.accumulation);
    gl.bindTexture(gl.TEXTURE_2D, sums.texture);
    gl.bindFramebuffer(gl.FRAMEBUFFER, framebuffer);
    gl.viewport(0, 0, width, height);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  }

  /** Draws into a temporary RGBA8 target of the given size and reads it back: sRGB, rows top to bottom. */
  read(sums: FloatTarget, sampleCount: number, options: DisplayOptions, width: number, height: number): Uint8Array {
    const gl = this.gl;
    const texture = gl.createTexture()!;
    gl.bindTexture(gl.TEXTURE_2D, texture);
    gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA8, width, height);
    const framebuffer = gl.createFramebuffer()!;
    gl.bindFramebuffer(gl.FRAMEBUFFER, framebuffer);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, texture, 0);
    this.draw(sums, sampleCount, options, framebuffer, width, height);
    const pixels = new Uint8Array(width * height * 4);
    gl.bindFramebuffer(gl.FRAMEBUFFER, framebuffer);
    gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.deleteFramebuffer(framebuffer);
    gl.deleteTexture(texture);
    return flipRows(pixels, width, height, 4);
  }

  dispose(): void {
    this.program.dispose();
  }
}
