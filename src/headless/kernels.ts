/**
 * Test kernels: a float target filled by one GLSL function of the renderer
 * (a sampler or a pdf), so browser tests can check the shader code itself
 * against its pdf (chi-square) or against a TypeScript reference.
 * Used by test/browser only; it ships in the headless page, never the library.
 */
import kernelFrag from '../shaders/test/kernels.frag?raw';
import { featureDefines, sceneDefines } from '../render/shaderChunks';
import { BASE_FEATURES } from '../render/packScene';
import { ALL_MATERIAL_FEATURES } from '../materials/registry';
import { SCENE_CHUNKS } from '../render/shaderSources';
import { runGuideKernel } from './guideKernels';
import { kernelProgram, runFullScreen } from './kernelHarness';
import { KERNELS, isGuideKernel, kernelMaterial, type KernelRequest } from './kernelRequest';

export { KERNELS, type KernelName, type KernelRequest } from './kernelRequest';

function kernelsProgram() {
  return kernelProgram('test/kernels.frag', () => {
    const defines = { ...sceneDefines(), ...featureDefines({ ...BASE_FEATURES, materials: ALL_MATERIAL_FEATURES }), ...Object.fromEntries(KERNELS.map((k, i) => [`KERNEL_${k.toUpperCase()}`, i])) };
    return { fragment: [...SCENE_CHUNKS, { name: 'test/kernels.frag', source: kernelFrag }], defines, sceneBlock: true };
  });
}

/** Runs a kernel; returns RGBA float32, rows bottom to top (pixel index = y * width + x). */
export function runKernel(request: KernelRequest): Float32Array {
  if (isGuideKernel(request.kernel)) return runGuideKernel({ ...request, kernel: request.kernel });
  const params = [0, 0, 0, 0].map((v, i) => request.params?.[i] ?? v);
  return runFullScreen(
    kernelsProgram(),
    {
      uKernel: KERNELS.indexOf(request.kernel),
      uParams: params,
      uMaterial: kernelMaterial(request),
      uWo: request.wo ?? [0, 0, 1],
      uGrid: [request.width, request.height],
      uSeed: request.seed ?? 1,
    },
    { uKernel: 'int', uParams: 'vec4', uMaterial: 'vec4', uWo: 'vec3', uGrid: 'vec2', uSeed: 'uint' },
    request.width,
    request.height,
    { label: `kernel ${request.kernel}` },
  );
}
