/**
 * Test kernels of the environment map's GLSL (src/shaders/lights/
 * environment_map.glsl): a float target filled by sampleEnvironment,
 * environmentPdf or environmentRadiance for a map sent by the test, so the
 * browser tests check the shader itself (chi-square against its pdf, the
 * mapping against the format's formula, the lookup against TypeScript).
 * Registers `window.pathtraceEnvironmentKernels` on the headless page.
 */
import mathGlsl from '../shaders/common/math.glsl?raw';
import rngGlsl from '../shaders/common/rng.glsl?raw';
import environmentGlsl from '../shaders/lights/environment_map.glsl?raw';
import kernelFrag from '../shaders/test/environment_kernels.frag?raw';
import { ENVIRONMENT_UNITS } from '../render/gl/textureUnits';
import { EnvironmentTextures } from '../render/environmentTextures';
import { buildEnvironmentDistribution } from '../scene/envmap/distribution';
import { kernelProgram, runFullScreen } from './kernelHarness';

export const ENVIRONMENT_KERNELS = ['sample', 'samplePdfs', 'pdfSphereGrid', 'pdfUvGrid', 'randomDirection', 'randomRadiance', 'radianceAt'] as const;
export type EnvironmentKernelName = (typeof ENVIRONMENT_KERNELS)[number];

export interface EnvironmentKernelRequest {
  kernel: EnvironmentKernelName;
  width: number;
  height: number;
  /** The map: width x height texels, rgb rows from the top. */
  map: { width: number; height: number; rgb: number[] };
  rotation: number;
  intensity: number;
  /** radianceAt: the direction (xyz); pdfUvGrid: x = shift of u. */
  params?: number[];
  seed?: number;
}

const UNITS = ENVIRONMENT_UNITS;

function environmentProgram() {
  return kernelProgram('test/environment_kernels.frag', () => {
    const defines = { LOW_DISCREPANCY: 0, HAS_ENV_MAP: 1, ...Object.fromEntries(ENVIRONMENT_KERNELS.map((k, i) => [`KERNEL_${k.toUpperCase()}`, i])) };
    const chunks = [
      { name: 'common/math.glsl', source: mathGlsl },
      { name: 'common/rng.glsl', source: rngGlsl },
      { name: 'lights/environment_map.glsl', source: environmentGlsl },
      { name: 'test/environment_kernels.frag', source: kernelFrag },
    ];
    return { fragment: chunks, defines };
  });
}

/** Runs a kernel; RGBA float32, rows bottom to top (pixel index = y * width + x). */
export function runEnvironmentKernel(request: EnvironmentKernelRequest): Float32Array {
  const kernel = environmentProgram();
  const image = { width: request.map.width, height: request.map.height, rgb: new Float32Array(request.map.rgb) };
  const textures = new EnvironmentTextures(kernel.gl, image, buildEnvironmentDistribution(image));
  try {
    const params = [0, 0, 0, 0].map((v, i) => request.params?.[i] ?? v);
    return runFullScreen(
      kernel,
      { uKernel: ENVIRONMENT_KERNELS.indexOf(request.kernel), uParams: params, uGrid: [request.width, request.height], uSeed: request.seed ?? 1 },
      { uKernel: 'int', uParams: 'vec4', uGrid: 'vec2', uSeed: 'uint' },
      request.width,
      request.height,
      {
        label: `environment kernel ${request.kernel}`,
        bind: (program) => {
          textures.bind(UNITS);
          textures.setUniforms(program, UNITS, request.rotation, request.intensity);
        },
      },
    );
  } finally {
    textures.dispose();
  }
}

function toBase64(data: Float32Array): string {
  const bytes = new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
  let binary = '';
  for (let i = 0; i < bytes.length; i += 0x8000) binary += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(binary);
}

export interface EnvironmentKernelApi {
  /** Runs a kernel; the float32 result as base64. */
  run(request: EnvironmentKernelRequest): string;
}

declare global {
  interface Window {
    pathtraceEnvironmentKernels: EnvironmentKernelApi;
  }
}

window.pathtraceEnvironmentKernels = { run: (request) => toBase64(runEnvironmentKernel(request)) };
