/**
 * The page's way to build a BVH without freezing the UI: one module worker
 * (worker.ts), started on first use, answering requests in order. Where
 * workers are unavailable (Node, tests) it builds on the calling thread.
 */
import type { BvhMeshInput } from './build';
import type { PackedBvh } from './pack';
import { buildAndPackGroups, type BvhWorkerResponse } from './worker';

let worker: Worker | null = null;
let nextId = 1;
const pending = new Map<number, { resolve: (p: PackedBvh) => void; reject: (e: Error) => void }>();

function startWorker(): Worker {
  const w = new Worker(new URL('./worker.ts', import.meta.url), { type: 'module' });
  w.onmessage = (event: MessageEvent<BvhWorkerResponse>) => {
    const request = pending.get(event.data.id);
    pending.delete(event.data.id);
    if (!request) return;
    if ('error' in event.data) request.reject(new Error(event.data.error));
    else request.resolve(event.data.packed);
  };
  w.onerror = (event) => {
    for (const request of pending.values()) request.reject(new Error(`BVH worker failed: ${event.message}`));
    pending.clear();
    worker = null;
  };
  return w;
}

/**
 * Builds and packs a BVH per group of meshes (src/render/bvh/groups.ts) in a
 * worker. The meshes' arrays are copied to the worker (the caller keeps them).
 */
export function buildBvhAsync(groups: BvhMeshInput[][]): Promise<PackedBvh> {
  if (typeof Worker === 'undefined') return Promise.resolve().then(() => buildAndPackGroups(groups));
  worker ??= startWorker();
  const id = nextId++;
  return new Promise((resolve, reject) => {
    pending.set(id, { resolve, reject });
    worker!.postMessage({ id, groups });
  });
}

/** Stops the worker (pending builds are rejected); the next build starts a new one. */
export function stopBvhWorker(): void {
  worker?.terminate();
  worker = null;
  for (const request of pending.values()) request.reject(new Error('BVH worker stopped'));
  pending.clear();
}
