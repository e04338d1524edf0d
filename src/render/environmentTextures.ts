/**
 * The GPU side of an environment map: the image (RGB32F) and its sampling
 * distribution (two RGBA32F alias tables) as textures, bound to texture
 * units chosen by the caller, and the uniforms that
 * src/shaders/lights/environment_map.glsl reads. Rotation and intensity are
 * plain uniforms: changing them re-uploads nothing and recompiles nothing.
 */
import type { EnvironmentImage } from '../scene/types';
import type { EnvironmentDistribution } from '../scene/envmap/distribution';
import type { Program } from './gl/program';
import { createDataTexture } from './gl/dataTexture';

/** GLSL types of the uniforms, in the form Program.setUniforms takes. */
export const ENVIRONMENT_UNIFORM_TYPES: Record<string, string> = {
  uEnvironmentMap: 'sampler2D',
  uEnvironmentMarginal: 'sampler2D',
  uEnvironmentConditional: 'sampler2D',
  uEnvironmentRotation: 'vec2',
  uEnvironmentIntensity: 'float',
};

/** Texture units of the three textures. */
export interface EnvironmentUnits {
  map: number;
  marginal: number;
  conditional: number;
}

export class EnvironmentTextureSizeError extends Error {
  constructor(what: string, width: number, height: number, max: number) {
    super(`the environment ${what} needs a ${width}x${height} texture, but this GPU allows at most ${max}x${max}`);
    this.name = 'EnvironmentTextureSizeError';
  }
}

export class EnvironmentTextures {
  private readonly textures: { map: WebGLTexture; marginal: WebGLTexture; conditional: WebGLTexture };

  /** Uploads the image and its distribution; throws EnvironmentTextureSizeError when the GPU's textures are too small. */
  constructor(
    private readonly gl: WebGL2RenderingContext,
    image: EnvironmentImage,
    distribution: EnvironmentDistribution,
  ) {
    const max = gl.getParameter(gl.MAX_TEXTURE_SIZE) as number;
    const check = (what: string, w: number, h: number) => {
      if (w > max || h > max) throw new EnvironmentTextureSizeError(what, w, h, max);
    };
    check('map', image.width, image.height);
    check('distribution', distribution.width, distribution.rows);
    if (image.rgb.length !== image.width * image.height * 3) throw new Error('environment image: rgb has the wrong length');
    this.textures = {
      map: createDataTexture(gl, image.width, image.height, image.rgb, 'rgb32f'),
      marginal: createDataTexture(gl, distribution.rows, 1, distribution.marginal),
      conditional: createDataTexture(gl, distribution.width, distribution.rows, distribution.conditional),
    };
  }

  /** Binds the three textures to their units (leaves the last unit active). */
  bind(units: EnvironmentUnits): void {
    const gl = this.gl;
    for (const key of ['map', 'marginal', 'conditional'] as const) {
      gl.activeTexture(gl.TEXTURE0 + units[key]);
      gl.bindTexture(gl.TEXTURE_2D, this.textures[key]);
    }
  }

  /** Sets the samplers' units, the rotation (degrees about +y) and the intensity on `program` (which must be in use). */
  setUniforms(program: Program, units: EnvironmentUnits, rotationDegrees: number, intensity: number): void {
    const angle = (rotationDegrees * Math.PI) / 180;
    program.setUniforms(
      {
        uEnvironmentMap: units.map,
        uEnvironmentMarginal: units.marginal,
        uEnvironmentConditional: units.conditional,
        uEnvironmentRotation: [Math.cos(angle), Math.sin(angle)],
        uEnvironmentIntensity: intensity,
      },
      ENVIRONMENT_UNIFORM_TYPES,
    );
  }

  dispose(): void {
    for (const texture of Object.values(this.textures)) this.gl.deleteTexture(texture);
  }
}
