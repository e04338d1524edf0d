/**
 * Test kernels of the caustic-guide mixture (sampleGuided / guidedPdf) and
 * of the BSDF sample weights: src/shaders/test/guide_kernels.frag compiled
 * with one caustic guide and the dielectric, the guide's mirror and light
 * written into the SceneBlock uniform block as the renderer writes them.
 * Used by test/browser only, through runKernel (./kernels.ts).
 */
import guideKernelFrag from '../shaders/test/guide_kernels.frag?raw';
import { Program } from '../render/gl/program';
import { FloatTarget } from '../render/gl/targets';
import { BLOCK_VEC4S, HEADER } from '../render/layout/scene';
import { featureDefines, sceneDefines } from '../render/shaderChunks';
import { BASE_FEATURES } from '../render/packScene';
import { ALL_MATERIAL_FEATURES } from '../materials/registry';
import { SCENE_CHUNKS, VERTEX_CHUNKS } from '../render/shaderSources';
import { createContext } from '../render/gl/context';
import { kernelMaterial, type KernelRequest } from './kernels';

/** guideSetup: pixel 0 = (local cone axis, 1 - cos half angle), others = guide probability. */
export const GUIDE_KERNELS = ['guideSetup', 'sampleGuided', 'weightGuided', 'weightBsdf', 'pdfGuided', 'pdfCap'] as const;
export type GuideKernelName = (typeof GUIDE_KERNELS)[number];

export function isGuideKernel(name: string): name is GuideKernelName {
  return (GUIDE_KERNELS as readonly string[]).includes(name);
}

let context: { gl: WebGL2RenderingContext; program: Program; block: WebGLBuffer } | null = null;

function guideContext() {
  if (!context) {
    const gl = createContext(new OffscreenCanvas(1, 1), false);
    const kernels = Object.fromEntries(GUIDE_KERNELS.map((k, i) => [`KERNEL_${k.toUpperCase()}`, i]));
    const defines = { ...sceneDefines(), ...featureDefines({ ...BASE_FEATURES, guides: 1, materials: ALL_MATERIAL_FEATURES }), ...kernels };
    const program = new Program(gl, VERTEX_CHUNKS, [...SCENE_CHUNKS, { name: 'test/guide_kernels.frag', source: guideKernelFrag }], defines);
    gl.bindVertexArray(gl.createVertexArray());
    const block = gl.createBuffer();
    gl.bindBuffer(gl.UNIFORM_BUFFER, block);
    gl.bufferData(gl.UNIFORM_BUFFER, BLOCK_VEC4S * 16, gl.DYNAMIC_DRAW);
    gl.uniformBlockBinding(program.handle, gl.getUniformBlockIndex(program.handle, 'SceneBlock'), 0);
    gl.bindBufferBase(gl.UNIFORM_BUFFER, 0, block);
    context = { gl, program, block };
  }
  return context;
}

export function runGuideKernel(request: KernelRequest & { kernel: GuideKernelName }): Float32Array {
  const { gl, program, block } = guideContext();
  // uGuides follows uHeader in the block: [mirror (centre, radius), light (centre, radius)].
  const guide = new Float32Array(8);
  guide.set((request.guide ?? []).slice(0, 8));
  gl.bindBuffer(gl.UNIFORM_BUFFER, block);
  gl.bufferSubData(gl.UNIFORM_BUFFER, HEADER.texels * 16, guide);
  const target = new FloatTarget(gl, request.width, request.height);
  const params = [0, 0, 0, 0].map((v, i) => request.params?.[i] ?? v);
  program.use().setUniforms(
    {
      uKernel: GUIDE_KERNELS.indexOf(request.kernel),
      uParams: params,
      uMaterial: kernelMaterial(request),
      uWo: request.wo ?? [0, 0, 1],
      uGrid: [request.width, request.height],
      uSeed: request.seed ?? 1,
      uPoint: request.point ?? [0, 0, 0],
      uNormal: request.normal ?? [0, 0, 1],
      uCap: request.cap ?? [0, 0, 1, 0.1],
    },
    { uKernel: 'int', uParams: 'vec4', uMaterial: 'vec4', uWo: 'vec3', uGrid: 'vec2', uSeed: 'uint', uPoint: 'vec3', uNormal: 'vec3', uCap: 'vec4' },
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
