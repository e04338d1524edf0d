/**
 * Web Worker: builds and packs a BVH off the page's main thread. Message in:
 * { id, meshes: BvhMeshInput[] }; out: { id, packed } or { id, error }.
 * The packed arrays are transferred, not copied.
 */
import { buildBvh, type BvhMeshInput } from './build';
import { packBvh, type PackedBvh } from './pack';

export interface BvhWorkerRequest {
  id: number;
  meshes: BvhMeshInput[];
}

export type BvhWorkerResponse = { id: number; packed: PackedBvh } | { id: number; error: string };

export function buildAndPack(meshes: BvhMeshInput[]): PackedBvh {
  return packBvh(buildBvh(meshes), meshes);
}

/** The arrays to transfer with a packed BVH. */
export function transferables(packed: PackedBvh): ArrayBuffer[] {
  return [packed.texture.data.buffer, packed.triangleOrder.buffer] as ArrayBuffer[];
}

// Only when loaded as a worker (no `document`): importing this file elsewhere has no effect.
if ('WorkerGlobalScope' in globalThis && typeof document === 'undefined') {
  self.onmessage = (event: MessageEvent<BvhWorkerRequest>) => {
    const { id, meshes } = event.data;
    try {
      const packed = buildAndPack(meshes);
      self.postMessage({ id, packed } satisfies BvhWorkerResponse, { transfer: transferables(packed) });
    } catch (error) {
      self.postMessage({ id, error: (error as Error).message } satisfies BvhWorkerResponse);
    }
  };
}
