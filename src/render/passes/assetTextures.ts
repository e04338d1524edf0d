/**
 * The GPU copies of a scene's decoded files: the environment map (image and
 * sampling distribution) and, later, the triangle BVH. Each is uploaded only
 * when the data itself changes (by identity), so scene edits re-upload
 * nothing here; rotation and intensity are plain uniforms.
 */
import { buildEnvironmentDistribution, type EnvironmentDistribution } from '../../scene/envmap';
import type { EnvironmentImage, Scene } from '../../scene/types';
import { EnvironmentTextures } from '../environmentTextures';
import type { Program } from '../gl/program';

/** Texture units (0 holds the running sums, 1 the scene data). */
const ENVIRONMENT_UNITS = { map: 2, marginal: 3, conditional: 4 };

/** Distributions by image: building one takes tens of milliseconds for a 2k map. */
const distributions = new WeakMap<EnvironmentImage, EnvironmentDistribution>();

export function environmentDistribution(image: EnvironmentImage): EnvironmentDistribution {
  let distribution = distributions.get(image);
  if (!distribution) {
    distribution = buildEnvironmentDistribution(image);
    distributions.set(image, distribution);
  }
  return distribution;
}

export class AssetTextures {
  private environment: { image: EnvironmentImage; textures: EnvironmentTextures } | null = null;

  constructor(private readonly gl: WebGL2RenderingContext) {}

  /** Uploads `image` (and its distribution) unless it is the one already uploaded; null frees it. */
  setEnvironmentMap(image: EnvironmentImage | null): void {
    if (this.environment?.image === image) return;
    this.environment?.textures.dispose();
    this.environment = image ? { image, textures: new EnvironmentTextures(this.gl, image, environmentDistribution(image)) } : null;
  }

  /** Sets the uniforms of the uploaded data on `program` (in use). */
  setUniforms(program: Program, scene: Scene): void {
    const e = scene.environment;
    if (this.environment && e && 'map' in e) this.environment.textures.setUniforms(program, ENVIRONMENT_UNITS, e.rotation, e.intensity);
  }

  /** Binds the textures to their units (leaves another unit than 0 active: callers set it back). */
  bind(): void {
    this.environment?.textures.bind(ENVIRONMENT_UNITS);
  }

  dispose(): void {
    this.setEnvironmentMap(null);
  }
}
