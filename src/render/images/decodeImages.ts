/**
 * Decodes texture images in a Worker (./imageWorker.ts) for the page and
 * the CLI's headless page: nothing decodes on the main thread, where a large
 * PNG would freeze the page. One Worker, created on first use, decodes the
 * images one after another (its messages queue).
 */
import { AssetError } from '../../scene/assetError';
import type { TextureImage } from '../../scene/texture/image';
import type { Readback } from './bitmapReadback';

export interface ImageWorkerRequest {
  id: number;
  bytes: ArrayBuffer;
  /** The JPEG/WebP read-back (bitmapReadback.ts); only the test that measures them sets it. */
  readback?: Readback;
}

export type ImageWorkerReply =
  | { id: number; ok: true; image: TextureImage; decodeMs: number }
  | { id: number; ok: false; message: string; assetError: boolean };

/** The last image decoded, for the tests and the bench (`globalThis.__imageTimings`). */
export interface ImageTimings {
  width: number;
  height: number;
  /** In the Worker. */
  decodeMs: number;
  /** From the request to the image back on this thread. */
  totalMs: number;
}

let worker: Worker | undefined;
let nextId = 0;
const pending = new Map<number, (reply: ImageWorkerReply) => void>();

function imageWorker(): Worker {
  if (worker) return worker;
  const created = new Worker(new URL('./imageWorker.ts', import.meta.url), { type: 'module' });
  created.onmessage = (event: MessageEvent<ImageWorkerReply>) => {
    pending.get(event.data.id)?.(event.data);
    pending.delete(event.data.id);
  };
  created.onerror = (event) => {
    // A Worker that cannot start or has died: fail what waits; the next request makes a new one.
    event.preventDefault();
    for (const [id, resolve] of pending) resolve({ id, ok: false, message: `the image decoder stopped${event.message ? ` (${event.message})` : ''}`, assetError: false });
    pending.clear();
    worker = undefined;
  };
  worker = created;
  return created;
}

/**
 * The decoded image of a file's bytes. Throws AssetError for a file the
 * decoder refuses (message without the scene path), Error otherwise.
 */
export async function decodeImageOffThread(bytes: Uint8Array, readback?: Readback): Promise<TextureImage> {
  const start = performance.now();
  const target = imageWorker();
  const copy = bytes.slice().buffer; // transferred: the caller keeps its bytes
  const reply = await new Promise<ImageWorkerReply>((resolve) => {
    const id = ++nextId;
    pending.set(id, resolve);
    target.postMessage({ id, bytes: copy, readback } satisfies ImageWorkerRequest, [copy]);
  });
  if (!reply.ok) throw reply.assetError ? new AssetError(reply.message) : new Error(reply.message);
  const { width, height } = reply.image;
  const timings: ImageTimings = { width, height, decodeMs: reply.decodeMs, totalMs: performance.now() - start };
  (globalThis as unknown as { __imageTimings?: ImageTimings }).__imageTimings = timings;
  return reply.image;
}
