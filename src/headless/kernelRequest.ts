/**
 * The kernels runKernel (./kernels.ts) runs and the request it takes, apart
 * from the kernels themselves: ./guideKernels.ts reads the same request, and
 * ./kernels.ts dispatches to it, so neither imports the other's module for
 * the shapes.
 */
import { MATERIAL_TEXELS, packMaterial } from '../materials/registry';
import type { Material } from '../scene/types';

export const KERNELS = ['sampleCone', 'sampleMaterial', 'pdfMaterial', 'sampleRectangle'] as const;

/** guideSetup: pixel 0 = (local cone axis, 1 - cos half angle), others = guide probability. */
export const GUIDE_KERNELS = ['guideSetup', 'sampleGuided', 'weightGuided', 'weightBsdf', 'pdfGuided', 'pdfCap'] as const;
export type GuideKernelName = (typeof GUIDE_KERNELS)[number];

export type KernelName = (typeof KERNELS)[number] | GuideKernelName;

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
  /** sampleRectangle: the rectangle's centre and half-axes u and v (9 numbers); the viewpoint is `wo`. */
  rect?: number[];
  /** pdfCap: the cap's axis (local frame) and half angle in radians. */
  cap?: [number, number, number, number];
}

/** The request's material as its packed record (zeros without one): the kernels' uMaterial. */
export function kernelMaterial(request: KernelRequest): Float32Array {
  return request.material ? packMaterial(request.material, false) : new Float32Array(MATERIAL_TEXELS * 4);
}

export function isGuideKernel(name: string): name is GuideKernelName {
  return (GUIDE_KERNELS as readonly string[]).includes(name);
}
