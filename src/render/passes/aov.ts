/**
 * The guide-buffer pass (src/shaders/aov.frag): accumulates the albedo and
 * the normal of the first non-specular hit, the auxiliary inputs of Open
 * Image Denoise, in two RGBA32F ping-pong pairs written by one draw (two
 * colour attachments). A separate program from the integrator, so the
 * colour path rate does not depend on whether the guides are kept.
 */
import { FloatTarget } from '../gl/targets';
import { Program } from '../gl/program';
import { TEXTURE_UNITS } from '../gl/textureUnits';
import type { SceneFeatures } from '../packScene';
import type { SamplerKind } from '../sampling';
import { assembleChunks, featureDefines, sceneDefines } from '../shaderChunks';
import { SCENE_CHUNKS, VERTEX_CHUNKS, shaderFile } from '../shaderSources';
import type { TracePass } from './trace';
import { FULL_SCREEN, type TileRun } from '../tiles';

const AOV_CHUNKS = [...SCENE_CHUNKS, ...assembleChunks(['camera.glsl', 'aov.frag'], shaderFile)];

const UNIFORM_TYPES: Record<string, string> = {
  uAlbedoSums: 'sampler2D',
  uNormalSums: 'sampler2D',
  uFirstSample: 'uint',
  uSamplesPerDraw: 'uint',
  uSeed: 'uint',
  uTiles: 'uvec4',
  uTileGrid: 'uvec3',
};

/** Texture units of the sums read (after the scene's). */
const ALBEDO_UNIT = TEXTURE_UNITS.albedoSums;
const NORMAL_UNIT = TEXTURE_UNITS.normalSums;

/** The guides' running sums, as Float32Arrays in GL's row order (bottom to top). */
export interface AovSums {
  albedo: Float32Array;
  normal: Float32Array;
}

/** One albedo and one normal target, with a framebuffer that writes both. */
class AovTargetPair {
  readonly albedo: FloatTarget;
  readonly normal: FloatTarget;
  readonly framebuffer: WebGLFramebuffer;

  constructor(private readonly gl: WebGL2RenderingContext, width: number, height: number) {
    this.albedo = new FloatTarget(gl, width, height);
    this.normal = new FloatTarget(gl, width, height);
    this.framebuffer = gl.createFramebuffer()!;
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.framebuffer);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, this.albedo.texture, 0);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT1, gl.TEXTURE_2D, this.normal.texture, 0);
    gl.drawBuffers([gl.COLOR_ATTACHMENT0, gl.COLOR_ATTACHMENT1]);
    const status = gl.checkFramebufferStatus(gl.FRAMEBUFFER);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    if (status !== gl.FRAMEBUFFER_COMPLETE && !gl.isContextLost()) {
      throw new Error(`two RGBA32F render targets are not supported (framebuffer status 0x${status.toString(16)})`);
    }
  }

  clear(): void {
    this.albedo.clear();
    this.normal.clear();
  }

  dispose(): void {
    this.albedo.dispose();
    this.normal.dispose();
    this.gl.deleteFramebuffer(this.framebuffer);
  }
}

export class AovPass {
  /** One program per scene feature set, compiled on first use (as TracePass's). */
  private readonly programs = new Map<string, Program>();
  private readonly defines: Record<string, string | number>;
  private pairs: [AovTargetPair, AovTargetPair];
  /** Samples per pixel in the sums. */
  samples = 0;

  constructor(
    private readonly gl: WebGL2RenderingContext,
    width: number,
    height: number,
    sampler: SamplerKind = 'kronecker',
  ) {
    this.defines = sceneDefines(sampler);
    this.pairs = [new AovTargetPair(gl, width, height), new AovTargetPair(gl, width, height)];
    this.clear();
  }

  get width(): number {
    return this.pairs[0].albedo.width;
  }

  get height(): number {
    return this.pairs[0].albedo.height;
  }

  /** Discards the sums (a new scene, size or seed). */
  clear(): void {
    this.pairs.forEach((pair) => pair.clear());
    this.samples = 0;
  }

  /** Replaces the targets by ones of a new size (cleared). */
  resize(width: number, height: number): void {
    this.pairs.forEach((pair) => pair.dispose());
    this.pairs = [new AovTargetPair(this.gl, width, height), new AovTargetPair(this.gl, width, height)];
    this.clear();
  }

  /**
   * Adds `samples` samples per pixel of the scene `trace` holds, numbered
   * from `this.samples`: over the whole image, at once; or (`tiles`) over a
   * run of tiles of a pass, which counts when the caller commits it, once
   * every tile is drawn.
   */
  draw(trace: TracePass, samples: number, seed: number, tiles: TileRun | null = null): void {
    const gl = this.gl;
    const program = this.programFor(trace.features);
    trace.bindScene(program);
    program.setUniforms(
      {
        uAlbedoSums: ALBEDO_UNIT,
        uNormalSums: NORMAL_UNIT,
        uFirstSample: this.samples,
        uSamplesPerDraw: samples,
        uSeed: seed >>> 0,
        ...(tiles ? tiles.layout.uniforms(tiles) : FULL_SCREEN),
      },
      UNIFORM_TYPES,
    );
    const [read, write] = this.pairs;
    gl.activeTexture(gl.TEXTURE0 + NORMAL_UNIT);
    gl.bindTexture(gl.TEXTURE_2D, read.normal.texture);
    gl.activeTexture(gl.TEXTURE0 + ALBEDO_UNIT);
    gl.bindTexture(gl.TEXTURE_2D, read.albedo.texture);
    gl.bindFramebuffer(gl.FRAMEBUFFER, write.framebuffer);
    gl.viewport(0, 0, write.albedo.width, write.albedo.height);
    if (tiles) gl.drawArrays(gl.POINTS, 0, tiles.count);
    else gl.drawArrays(gl.TRIANGLES, 0, 3);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    // No sampler keeps pointing at a target the next draw writes.
    for (const unit of [NORMAL_UNIT, ALBEDO_UNIT]) {
      gl.activeTexture(gl.TEXTURE0 + unit);
      gl.bindTexture(gl.TEXTURE_2D, null);
    }
    gl.activeTexture(gl.TEXTURE0);
    if (!tiles) this.commit(samples);
  }

  /** Counts a pass of `samples` samples per pixel whose tiles are all drawn (draw with tiles). */
  commit(samples: number): void {
    this.pairs = [this.pairs[1], this.pairs[0]];
    this.samples += samples;
  }

  /** The running sums (rgb: sum of valid samples; a: count of rejected ones), rows bottom to top. */
  readSums(): AovSums {
    const [read] = this.pairs;
    return { albedo: read.albedo.read(), normal: read.normal.read() };
  }

  dispose(): void {
    for (const program of this.programs.values()) program.dispose();
    this.pairs.forEach((pair) => pair.dispose());
  }

  private programFor(features: SceneFeatures): Program {
    // The guides are never used here: one variant serves every guide count.
    const key = JSON.stringify({ ...features, guides: 0 });
    let program = this.programs.get(key);
    if (!program) {
      program = new Program(this.gl, VERTEX_CHUNKS, AOV_CHUNKS, { ...this.defines, ...featureDefines({ ...features, guides: 0 }) });
      this.programs.set(key, program);
    }
    return program;
  }
}
