/**
 * Test kernels of the caustic-guide mixture (sampleGuided / guidedPdf) and
 * of the BSDF sample weights: src/shaders/test/guide_kernels.frag compiled
 * with one caustic guide and every material kind, the guide's mirror and light
 * written into the SceneBlock uniform block as the renderer writes them.
 * Used by test/browser only, through runKernel (./kernels.ts).
 */
import guideKernelFrag from '../shaders/test/guide_kernels.frag?raw';
import { HEADER } from '../render/layout/scene';
import { featureDefines, sceneDefines } from '../render/shaderChunks';
import { BASE_FEATURES } from '../render/packScene';
import { ALL_MATERIAL_FEATURES } from '../materials/registry';
import { SCENE_CHUNKS } from '../render/shaderSources';
import { kernelProgram, runFullScreen } from './kernelHarness';
import { GUIDE_KERNELS, kernelMaterial, type GuideKernelName, type KernelRequest } from './kernelRequest';

export { GUIDE_KERNELS, isGuideKernel, type GuideKernelName } from './kernelRequest';

function guideProgram() {
  return kernelProgram('test/guide_kernels.frag', () => {
    const kernels = Object.fromEntries(GUIDE_KERNELS.map((k, i) => [`KERNEL_${k.toUpperCase()}`, i]));
    const defines = { ...sceneDefines(), ...featureDefines({ ...BASE_FEATURES, guides: 1, materials: ALL_MATERIAL_FEATURES }), ...kernels };
    return { fragment: [...SCENE_CHUNKS, { name: 'test/guide_kernels.frag', source: guideKernelFrag }], defines, sceneBlock: true };
  });
}

export function runGuideKernel(request: KernelRequest & { kernel: GuideKernelName }): Float32Array {
  const kernel = guideProgram();
  const { gl } = kernel;
  // uGuides follows uHeader in the block: [mirror (centre, radius), light (centre, radius)].
  const guide = new Float32Array(8);
  guide.set((request.guide ?? []).slice(0, 8));
  gl.bindBuffer(gl.UNIFORM_BUFFER, kernel.sceneBlock);
  gl.bufferSubData(gl.UNIFORM_BUFFER, HEADER.texels * 16, guide);
  const params = [0, 0, 0, 0].map((v, i) => request.params?.[i] ?? v);
  return runFullScreen(
    kernel,
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
    request.width,
    request.height,
    { label: `kernel ${request.kernel}` },
  );
}
