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
import { ALL_LIGHT_FEATURES } from '../lights/registry';
import { SCENE_CHUNKS } from '../render/shaderSources';
import { runGuideKernel } from './guideKernels';
import { kernelProgram, runFullScreen } from './kernelHarness';
import { KERNELS, isGuideKernel, kernelMaterial, type KernelRequest } from './kernelRequest';

export { KERNELS, type KernelName, type KernelRequest } from './kernelRequest';

function kernelsProgram() {
  return kernelProgram('test/kernels.frag', () => {
    const defines = { ...sceneDefines(), ...featureDefines({ ...BASE_FEATURES, materials: ALL_MATERIAL_FEATURES, lights: ALL_LIGHT_FEATURES }), ...Object.fromEntries(KERNELS.map((k, i) => [`KERNEL_${k.toUpperCase()}`, i])) };
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
      uRect: rectUniform(request.rect),
    },
    { uKernel: 'int', uParams: 'vec4', uMaterial: 'vec4', uWo: 'vec3', uGrid: 'vec2', uSeed: 'uint', uRect: 'vec4' },
    request.width,
    request.height,
    { label: `kernel ${request.kernel}` },
  );
}

/** The rectangle of sampleRectangle as three vec4s (centre, u, v). */
function rectUniform(rect: number[] = []): Float32Array {
  const out = new Float32Array(12);
  for (let i = 0; i < 3; i++) out.set([rect[i * 3] ?? 0, rect[i * 3 + 1] ?? 0, rect[i * 3 + 2] ?? 0], i * 4);
  return out;
}
