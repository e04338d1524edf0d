/**
 * Decodes environment maps for the page in a Worker (src/app/mapWorker.ts):
 * the file's pixels and the importance-sampling distribution are built off
 * the main thread, and the distribution is handed to the renderer's cache so
 * the upload does not build it again. Without Workers it decodes in place.
 */
import { AssetError } from '../scene/assetError';
import { buildEnvironmentDistribution, decodeEnvironmentMap, type EnvironmentDistribution } from '../scene/envmap';
import type { EnvironmentImage } from '../scene/types';

export interface MapWorkerRequest {
  id: number;
  bytes: ArrayBuffer;
  name: string;
}

export type MapWorkerReply =
  | { id: number; ok: true; image: EnvironmentImage; distribution: EnvironmentDistribution; decodeMs: number; distributionMs: number }
  | { id: number; ok: false; message: string; assetError: boolean };

/** Times of the last map decoded (for the bench and the tests: `window.__mapTimings`). */
export interface MapTimings {
  name: string;
  width: number;
  height: number;
  /** In the Worker. */
  decodeMs: number;
  distributionMs: number;
  /** From the request to the decoded map back on the main thread. */
  totalMs: number;
  offMainThread: boolean;
  /** Main thread: applying the decoded map to the scene (the texture upload is queued here), when it was applied. */
  applyMs?: number;
}

let worker: Worker | null | undefined;
let nextId = 0;
const pending = new Map<number, (reply: MapWorkerReply) => void>();

function mapWorker(): Worker | null {
  if (worker !== undefined) return worker;
  try {
    worker = new Worker(new URL('./mapWorker.ts', import.meta.url), { type: 'module' });
    worker.onmessage = (event: MessageEvent<MapWorkerReply>) => {
      pending.get(event.data.id)?.(event.data);
      pending.delete(event.data.id);
    };
    worker.onerror = () => {
      // A Worker that cannot start: fail what waits and decode in place from now on.
      for (const [id, resolve] of pending) resolve({ id, ok: false, message: 'the map decoder stopped', assetError: false });
      pending.clear();
      worker = null;
    };
  } catch {
    worker = null;
  }
  return worker;
}

function record(timings: MapTimings): void {
  (globalThis as unknown as { __mapTimings?: MapTimings }).__mapTimings = timings;
}

/** Adds to the timings of the last map decoded (see MapTimings.applyMs). */
export function recordApplyTime(name: string, applyMs: number): void {
  const timings = (globalThis as unknown as { __mapTimings?: MapTimings }).__mapTimings;
  if (timings?.name === name) timings.applyMs = applyMs;
}

/**
 * The decoded map of `bytes` (a file named `name`). Throws AssetError for a
 * file the decoder refuses (message without the scene path), Error otherwise.
 */
export async function decodeMap(bytes: Uint8Array, name: string): Promise<EnvironmentImage> {
  const start = performance.now();
  const target = mapWorker();
  if (!target) {
    const image = decodeEnvironmentMap(bytes, name);
    const decoded = performance.now();
    image.distribution = buildEnvironmentDistribution(image);
    const end = performance.now();
    record({ name, width: image.width, height: image.height, decodeMs: decoded - start, distributionMs: end - decoded, totalMs: end - start, offMainThread: false });
    return image;
  }
  const copy = bytes.slice().buffer; // transferred: the caller keeps its bytes
  const reply = await new Promise<MapWorkerReply>((resolve) => {
    const id = ++nextId;
    pending.set(id, resolve);
    target.postMessage({ id, bytes: copy, name } satisfies MapWorkerRequest, [copy]);
  });
  if (!reply.ok) throw reply.assetError ? new AssetError(reply.message) : new Error(reply.message);
  reply.image.distribution = reply.distribution;
  const { width, height } = reply.image;
  record({ name, width, height, decodeMs: reply.decodeMs, distributionMs: reply.distributionMs, totalMs: performance.now() - start, offMainThread: true });
  return reply.image;
}
