/**
 * Test kernels: a float target filled by one GLSL function of the renderer
 * (a sampler or a pdf), so browser tests can check the shader code itself
 * against its pdf (chi-square) or against a TypeScript reference.
 * Used by test/browser only; it ships in the headless page, never the library.
 */
import kernelFrag from '../shaders/test/kernels.frag?raw';
import { Program } from '../render/gl/program';
import { FloatTarget } from '../render/gl/targets';
import { BLOCK_VEC4S } from '../render/layout/scene';
import { featureDefines, sceneDefines } from '../render/shaderChunks';
import { BASE_FEATURES } from '../render/packScene';
import { ALL_MATERIAL_FEATURES, MATERIAL_TEXELS, packMaterial } from '../materials/registry';
import type { Material } from '../scene/types';
import { SCENE_CHUNKS, VERTEX_CHUNKS } from '../render/shaderSources';
import { createContext } from '../render/gl/context';
import { GUIDE_KERNELS, isGuideKernel, runGuideKernel } from './guideKernels';

export const KERNELS = ['sampleCone', 'sampleMaterial', 'pdfMaterial'] as const;
export type KernelName = (typeof KERNELS)[number] | (typeof GUIDE_KERNELS)[number];

export interface KernelRequest {
  kernel: KernelName;
  width: number;
  height: number;
  /** Kernel parameters: cone: [oneMinusCosMax]. */
  params?: number[];
  /** The material of the material and guide kernels (a normalized scene-format material). */
  material?: Material;
  /** Outgoing direction (local frame) for the material kernels. */
  wo?: [number, number, number];
  seed?: number;
  /** Guide kernels (./guideKernels.ts): the vertex, its normal, and the guide's mirror and light (centre, radius each). */
  point?: [number, number, number];
  normal?: [number, number, number];
  guide?: number[];
  /** pdfCap: the cap's axis (local frame) and half angle in radians. */
  cap?: [number, number, number, number];
}

/** The request's material as its packed record (zeros without one). */
export function kernelMaterial(request: KernelRequest): Float32Array {
  return request.material ? packMaterial(request.material, false) : new Float32Array(MATERIAL_TEXELS * 4);
}

let context: { gl: WebGL2RenderingContext; program: Program } | null = null;

function kernelContext() {
  if (!context) {
    const gl = createContext(new OffscreenCanvas(1, 1), false);
    const defines = { ...sceneDefines(), ...featureDefines({ ...BASE_FEATURES, guides: 0, materials: ALL_MATERIAL_FEATURES }), ...Object.fromEntries(KERNELS.map((k, i) => [`KERNEL_${k.toUpperCase()}`, i])) };
    const program = new Program(gl, VERTEX_CHUNKS, [...SCENE_CHUNKS, { name: 'test/kernels.frag', source: kernelFrag }], defines);
    gl.bindVertexArray(gl.createVertexArray());
    // The scene chunks declare the SceneBlock uniform block; a draw with an
    // active block and no buffer bound is an error, so bind an empty scene.
    const sceneBuffer = gl.createBuffer();
    gl.bindBuffer(gl.UNIFORM_BUFFER, sceneBuffer);
    gl.bufferData(gl.UNIFORM_BUFFER, BLOCK_VEC4S * 16, gl.STATIC_DRAW);
    const blockIndex = gl.getUniformBlockIndex(program.handle, 'SceneBlock');
    if (blockIndex !== gl.INVALID_INDEX) gl.uniformBlockBinding(program.handle, blockIndex, 0);
    gl.bindBufferBase(gl.UNIFORM_BUFFER, 0, sceneBuffer);
    context = { gl, program };
  }
  return context;
}

/** Runs a kernel; returns RGBA float32, rows bottom to top (pixel index = y * width + x). */
export function runKernel(request: KernelRequest): Float32Array {
  if (isGuideKernel(request.kernel)) return runGuideKernel({ ...request, kernel: request.kernel });
  const { gl, program } = kernelContext();
  const target = new FloatTarget(gl, request.width, request.height);
  const params = [0, 0, 0, 0].map((v, i) => request.params?.[i] ?? v);
  program.use().setUniforms(
    {
      uKernel: KERNELS.indexOf(request.kernel),
      uParams: params,
      uMaterial: kernelMaterial(request),
      uWo: request.wo ?? [0, 0, 1],
      uGrid: [request.width, request.height],
      uSeed: request.seed ?? 1,
    },
    { uKernel: 'int', uParams: 'vec4', uMaterial: 'vec4', uWo: 'vec3', uGrid: 'vec2', uSeed: 'uint' },
  );
  gl.bindFramebuffer(gl.FRAMEBUFFER, target.framebuffer);
  gl.viewport(0, 0, request.width, request.height);
  gl.drawArrays(gl.TRIANGLES, 0, 3);
  const error = gl.getError();
  if (error !== gl.NO_ERROR) throw new Error(`kernel ${request.kernel}: WebGL error 0x${error.toString(16)}`);
  const data = target.read();
  target.dispose();
  return data;
}
