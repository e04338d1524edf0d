/**
 * Decodes a model file in a Web Worker (meshDecodeWorker.ts), so a large
 * file does not freeze the page (a 24 MB, 1M-triangle PLY took seconds on
 * the page's thread). A file the decoder rejects rejects with its
 * AssetError; if the worker itself fails (no workers, a resource it cannot
 * load), the file is decoded on the page's thread instead.
 */
import { AssetError } from '../scene/assetError';
import { decodeMesh } from '../scene/mesh';
import type { TriangleMesh } from '../scene/types';
import type { DecodeResponse } from './meshDecodeWorker';

let worker: Worker | null = null;
let nextId = 1;
const pending = new Map<number, (response: DecodeResponse | null) => void>();

function startWorker(): Worker {
  const w = new Worker(new URL('./meshDecodeWorker.ts', import.meta.url), { type: 'module' });
  w.onmessage = (event: MessageEvent<DecodeResponse>) => {
    pending.get(event.data.id)?.(event.data);
    pending.delete(event.data.id);
  };
  w.onerror = () => {
    for (const done of pending.values()) done(null);
    pending.clear();
    worker = null;
  };
  return w;
}

export async function decodeMeshOffThread(bytes: Uint8Array, fileName: string): Promise<TriangleMesh> {
  if (typeof Worker === 'undefined') return decodeMesh(bytes, fileName);
  worker ??= startWorker();
  const id = nextId++;
  const response = await new Promise<DecodeResponse | null>((resolve) => {
    pending.set(id, resolve);
    // A copy goes to the worker: the caller keeps its bytes for the fallback.
    worker!.postMessage({ id, bytes, fileName });
  });
  if (response && 'mesh' in response) return response.mesh;
  if (response && response.assetError) throw new AssetError(response.error);
  return decodeMesh(bytes, fileName);
}
