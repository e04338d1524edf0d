/**
 * The harness of the headless test kernels (./kernels.ts, ./guideKernels.ts,
 * ./environmentKernels.ts, ./bvhKernels.ts): one WebGL2 context, a program
 * per kernel source (the full-screen triangle and a test .frag after the
 * chunks it exercises), compiled once per key, and a full-screen draw into a
 * float target read back. Used by test/browser and bench/ through the
 * headless page only; it ships in the headless page, never the library.
 */
import { Program } from '../render/gl/program';
import type { ShaderChunk } from '../render/gl/shaderSource';
import { FloatTarget } from '../render/gl/targets';
import { createContext } from '../render/gl/context';
import { BLOCK_VEC4S } from '../render/layout/scene';
import { VERTEX_CHUNKS } from '../render/shaderSources';

/** Binding point of the SceneBlock uniform block of a kernel built from the scene chunks. */
const SCENE_BLOCK_BINDING = 0;

export interface KernelProgram {
  readonly gl: WebGL2RenderingContext;
  readonly program: Program;
  /**
   * The SceneBlock buffer (BLOCK_VEC4S vec4s, zeros until written) of a
   * kernel built from the scene chunks, bound before each draw: a draw with
   * an active block and no buffer bound is an error. Null for the others.
   */
  readonly sceneBlock: WebGLBuffer | null;
}

export interface KernelProgramSpec {
  /** The fragment shader's chunks (the vertex shader is the full-screen triangle). */
  fragment: ShaderChunk[];
  defines: Record<string, string | number>;
  /** The chunks declare the SceneBlock uniform block (the scene chunks do). */
  sceneBlock?: boolean;
}

let context: WebGL2RenderingContext | null = null;
const programs = new Map<string, KernelProgram>();

/** The kernels' context (an empty vertex array bound: the full-screen triangle has no attributes). */
export function kernelContext(): WebGL2RenderingContext {
  if (!context) {
    context = createContext(new OffscreenCanvas(1, 1), false);
    context.bindVertexArray(context.createVertexArray());
  }
  return context;
}

/** The program of `key`, compiled from `spec()` on first use, then cached. */
export function kernelProgram(key: string, spec: () => KernelProgramSpec): KernelProgram {
  let kernel = programs.get(key);
  if (!kernel) {
    const gl = kernelContext();
    const { fragment, defines, sceneBlock } = spec();
    const program = new Program(gl, VERTEX_CHUNKS, fragment, defines);
    let block: WebGLBuffer | null = null;
    if (sceneBlock) {
      block = gl.createBuffer();
      gl.bindBuffer(gl.UNIFORM_BUFFER, block);
      gl.bufferData(gl.UNIFORM_BUFFER, BLOCK_VEC4S * 16, gl.DYNAMIC_DRAW);
      const blockIndex = gl.getUniformBlockIndex(program.handle, 'SceneBlock');
      if (blockIndex !== gl.INVALID_INDEX) gl.uniformBlockBinding(program.handle, blockIndex, SCENE_BLOCK_BINDING);
    }
    kernel = { gl, program, sceneBlock: block };
    programs.set(key, kernel);
  }
  return kernel;
}

export interface FullScreenOptions {
  /** Names the kernel in the WebGL error message. */
  label: string;
  /** Binds the kernel's textures (the program is in use; the float target already exists, so it cannot displace them). */
  bind?: (program: Program) => void;
  /** Timed draws after the first: then the result is their mean time in ms instead of the pixels. */
  timedDraws?: number;
}

/**
 * Draws the full-screen triangle with `kernel` into a width x height float
 * target and reads it back: RGBA float32, rows bottom to top (pixel index =
 * y * width + x). Throws on a WebGL error.
 */
export function runFullScreen(
  kernel: KernelProgram,
  uniforms: Parameters<Program['setUniforms']>[0],
  types: Record<string, string>,
  width: number,
  height: number,
  options: FullScreenOptions & { timedDraws?: undefined },
): Float32Array;
export function runFullScreen(
  kernel: KernelProgram,
  uniforms: Parameters<Program['setUniforms']>[0],
  types: Record<string, string>,
  width: number,
  height: number,
  options: FullScreenOptions,
): Float32Array | number;
export function runFullScreen(
  kernel: KernelProgram,
  uniforms: Parameters<Program['setUniforms']>[0],
  types: Record<string, string>,
  width: number,
  height: number,
  options: FullScreenOptions,
): Float32Array | number {
  const { gl, program, sceneBlock } = kernel;
  // Every kernel starts from unit 0 active, as with a context of its own.
  gl.activeTexture(gl.TEXTURE0);
  const target = new FloatTarget(gl, width, height);
  try {
    program.use();
    options.bind?.(program);
    program.setUniforms(uniforms, types);
    if (sceneBlock) gl.bindBufferBase(gl.UNIFORM_BUFFER, SCENE_BLOCK_BINDING, sceneBlock);
    gl.bindFramebuffer(gl.FRAMEBUFFER, target.framebuffer);
    gl.viewport(0, 0, width, height);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    if (options.timedDraws) {
      target.read(); // waits for the first draw (compile, upload)
      const start = performance.now();
      for (let i = 0; i < options.timedDraws; i++) {
        gl.bindFramebuffer(gl.FRAMEBUFFER, target.framebuffer); // read() unbinds it
        gl.drawArrays(gl.TRIANGLES, 0, 3);
        target.read(); // one draw at a time, finished
      }
      return (performance.now() - start) / options.timedDraws;
    }
    const error = gl.getError();
    if (error !== gl.NO_ERROR) throw new Error(`${options.label}: WebGL error 0x${error.toString(16)}`);
    return target.read();
  } finally {
    target.dispose();
  }
}
