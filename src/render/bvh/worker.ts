/**
 * Web Worker: builds and packs a BVH off the page's main thread. Message in:
 * { id, groups: BvhMeshInput[][] } (src/render/bvh/groups.ts: one BVH per
 * group); out: { id, packed } or { id, error }.
 * The packed arrays are transferred, not copied.
 */
import { buildBvh, type BvhMeshInput } from './build';
import { packBvhGroups, type PackedBvh } from './pack';

export interface BvhWorkerRequest {
  id: number;
  groups: BvhMeshInput[][];
}

export type BvhWorkerResponse = { id: number; packed: PackedBvh } | { id: number; error: string };

/** One BVH over `meshes`, packed. */
export function buildAndPack(meshes: BvhMeshInput[]): PackedBvh {
  return buildAndPackGroups([meshes]);
}

/** A BVH per group (none may be empty), packed into one texture. */
export function buildAndPackGroups(groups: BvhMeshInput[][]): PackedBvh {
  return packBvhGroups(groups.map((meshes) => ({ bvh: buildBvh(meshes), meshes })));
}

/** The arrays to transfer with a packed BVH. */
export function transferables(packed: PackedBvh): ArrayBuffer[] {
  return [packed.texture.data.buffer, packed.triangleOrder.buffer] as ArrayBuffer[];
}

// Only when loaded as a worker (no `document`): importing this file elsewhere has no effect.
if ('WorkerGlobalScope' in globalThis && typeof document === 'undefined') {
  self.onmessage = (event: MessageEvent<BvhWorkerRequest>) => {
    const { id, groups } = event.data;
    try {
      const packed = buildAndPackGroups(groups);
      self.postMessage({ id, packed } satisfies BvhWorkerResponse, { transfer: transferables(packed) });
    } catch (error) {
      self.postMessage({ id, error: (error as Error).message } satisfies BvhWorkerResponse);
    }
  };
}
