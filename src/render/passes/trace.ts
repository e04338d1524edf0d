/** The path-tracing pass: adds samples to the running sums in a ping-pong pair. */
import fullscreenVert from '../../shaders/fullscreen.vert?raw';
import mathGlsl from '../../shaders/common/math.glsl?raw';
import rngGlsl from '../../shaders/common/rng.glsl?raw';
import samplingGlsl from '../../shaders/common/sampling.glsl?raw';
import layoutGlsl from '../../shaders/scene/layout.glsl?raw';
import intersectGlsl from '../../shaders/scene/intersect.glsl?raw';
import ggxGlsl from '../../shaders/bsdf/ggx.glsl?raw';
import materialGlsl from '../../shaders/bsdf/material.glsl?raw';
import causticGuideGlsl from '../../shaders/lights/caustic_guide.glsl?raw';
import sphereLightGlsl from '../../shaders/lights/sphere_light.glsl?raw';
import cameraGlsl from '../../shaders/camera.glsl?raw';
import integratorGlsl from '../../shaders/integrator.glsl?raw';
import traceFrag from '../../shaders/trace.frag?raw';
import { type CameraFrame, cameraFrame, inverseViewProjection } from '../../scene/camera';
import type { Scene } from '../../scene/types';
import { Program } from '../gl/program';
import type { ShaderChunk } from '../gl/shaderSource';
import type { PingPong } from '../gl/targets';
import { BLOCK, layoutDefines, type SamplerKind } from '../layout';
import { causticGuides, packScene } from '../packScene';

export const VERTEX_CHUNKS: ShaderChunk[] = [{ name: 'fullscreen.vert', source: fullscreenVert }];

/** The chunks every kernel that touches the scene needs, in dependency order. */
export const SCENE_CHUNKS: ShaderChunk[] = [
  { name: 'common/math.glsl', source: mathGlsl },
  { name: 'common/rng.glsl', source: rngGlsl },
  { name: 'common/sampling.glsl', source: samplingGlsl },
  { name: 'scene/layout.glsl', source: layoutGlsl },
  { name: 'scene/intersect.glsl', source: intersectGlsl },
  { name: 'bsdf/ggx.glsl', source: ggxGlsl },
  { name: 'bsdf/material.glsl', source: materialGlsl },
  { name: 'lights/caustic_guide.glsl', source: causticGuideGlsl },
  { name: 'lights/sphere_light.glsl', source: sphereLightGlsl },
];

const TRACE_CHUNKS: ShaderChunk[] = [
  ...SCENE_CHUNKS,
  { name: 'camera.glsl', source: cameraGlsl },
  { name: 'integrator.glsl', source: integratorGlsl },
  { name: 'trace.frag', source: traceFrag },
];

const UNIFORM_TYPES: Record<string, string> = {
  uInverseViewProjection: 'mat4',
  uCameraPosition: 'vec3',
  uCameraRight: 'vec3',
  uCameraUp: 'vec3',
  uCameraForward: 'vec3',
  uAperture: 'float',
  uFocusDistance: 'float',
  uResolution: 'vec2',
  uMaxBounces: 'int',
  uAccumulation: 'sampler2D',
  uFirstSample: 'uint',
  uSamplesPerDraw: 'uint',
  uSeed: 'uint',
  uSceneData: 'sampler2D',
};

const SCENE_BLOCK_BINDING = 0;
/** Texture unit of the scene data texture (unit 0 holds the running sums). */
const SCENE_TEXTURE_UNIT = 1;

export class TracePass {
  /**
   * One program per number of caustic guides compiled in (0..MAX_GUIDES; see
   * lights/caustic_guide.glsl). Those for 0 and 1 guide are compiled up front,
   * so common edits never compile; the two-guide one (two guiding mirrors or
   * lights in one scene) on first use.
   */
  private readonly programs = new Map<number, Program>();
  /** The variant for the current scene. */
  private program: Program;
  private readonly sceneBuffer: WebGLBuffer;
  /**
   * The same packed scene as the uniform block, one RGBA32F texel per vec4
   * (row 0): the loops over spheres and lights index it dynamically, and in
   * SwiftShader a texelFetch is much cheaper than a dynamically indexed,
   * bounds-checked uniform-block read (per-lane conditional loads).
   */
  private readonly sceneTexture: WebGLTexture;

  private readonly defines: Record<string, string | number>;

  constructor(
    private readonly gl: WebGL2RenderingContext,
    sampler: SamplerKind = 'kronecker',
    russianRoulette = false,
  ) {
    this.defines = {
      ...layoutDefines(),
      LOW_DISCREPANCY: sampler === 'kronecker' ? 1 : 0,
      RUSSIAN_ROULETTE: russianRoulette ? 1 : 0,
    };
    this.program = this.programFor(0);
    this.programFor(1);
    this.sceneBuffer = gl.createBuffer()!;
    gl.bindBuffer(gl.UNIFORM_BUFFER, this.sceneBuffer);
    gl.bufferData(gl.UNIFORM_BUFFER, BLOCK.size * 16, gl.DYNAMIC_DRAW);
    gl.bindBuffer(gl.UNIFORM_BUFFER, null);
    this.sceneTexture = gl.createTexture()!;
    gl.bindTexture(gl.TEXTURE_2D, this.sceneTexture);
    gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, BLOCK.size, 1);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    gl.bindTexture(gl.TEXTURE_2D, null);
  }

  private programFor(guides: number): Program {
    let program = this.programs.get(guides);
    if (!program) {
      program = new Program(this.gl, VERTEX_CHUNKS, TRACE_CHUNKS, { ...this.defines, CAUSTIC_GUIDES: guides });
      const blockIndex = this.gl.getUniformBlockIndex(program.handle, 'SceneBlock');
      this.gl.uniformBlockBinding(program.handle, blockIndex, SCENE_BLOCK_BINDING);
      this.programs.set(guides, program);
    }
    return program;
  }

  /** Uploads the scene: geometry and materials to the uniform block, camera to uniforms. */
  setScene(scene: Scene, width: number, height: number): void {
    const gl = this.gl;
    gl.bindBuffer(gl.UNIFORM_BUFFER, this.sceneBuffer);
    const packed = packScene(scene);
    gl.bufferSubData(gl.UNIFORM_BUFFER, 0, packed);
    gl.bindBuffer(gl.UNIFORM_BUFFER, null);
    gl.bindTexture(gl.TEXTURE_2D, this.sceneTexture);
    gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, BLOCK.size, 1, gl.RGBA, gl.FLOAT, packed);
    gl.bindTexture(gl.TEXTURE_2D, null);
    this.program = this.programFor(causticGuides(scene).length);
    const frame = cameraFrame(scene.camera);
    for (const program of this.programs.values()) this.setCameraUniforms(program, scene, frame, width, height);
  }

  private setCameraUniforms(program: Program, scene: Scene, frame: CameraFrame, width: number, height: number): void {
    program.use().setUniforms(
      {
        uInverseViewProjection: inverseViewProjection(scene.camera, width / height),
        uCameraPosition: frame.position,
        uCameraRight: frame.right,
        uCameraUp: frame.up,
        uCameraForward: frame.forward,
        uAperture: scene.camera.aperture,
        uFocusDistance: frame.focusDistance,
        uResolution: [width, height],
        uMaxBounces: scene.render.maxBounces,
        uAccumulation: 0,
        uSceneData: SCENE_TEXTURE_UNIT,
      },
      UNIFORM_TYPES,
    );
  }

  /** One draw: adds `samples` samples per pixel, numbered from `firstSample`. */
  draw(targets: PingPong, firstSample: number, samples: number, seed: number): void {
    const gl = this.gl;
    this.program.use().setUniforms(
      { uFirstSample: firstSample, uSamplesPerDraw: samples, uSeed: seed >>> 0 },
      UNIFORM_TYPES,
    );
    gl.bindBufferBase(gl.UNIFORM_BUFFER, SCENE_BLOCK_BINDING, this.sceneBuffer);
    gl.activeTexture(gl.TEXTURE0 + SCENE_TEXTURE_UNIT);
    gl.bindTexture(gl.TEXTURE_2D, this.sceneTexture);
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, targets.read.texture);
    gl.bindFramebuffer(gl.FRAMEBUFFER, targets.write.framebuffer);
    gl.viewport(0, 0, targets.write.width, targets.write.height);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    targets.swap();
  }

  dispose(): void {
    for (const program of this.programs.values()) program.dispose();
    this.gl.deleteBuffer(this.sceneBuffer);
    this.gl.deleteTexture(this.sceneTexture);
  }
}
