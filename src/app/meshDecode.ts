/**
 * Decodes a model file in a Web Worker (meshDecodeWorker.ts), so a large
 * file does not freeze the page (a 24 MB, 1M-triangle PLY took seconds on
 * the page's thread). The files opened with it go along (Blobs: the Worker
 * reads only those the model names: a .gltf's .bin, an OBJ's .mtl), and the
 * decoded triangles remember which it read (companionFiles.ts). A file the
 * decoder rejects rejects with its AssetError; if the worker itself fails
 * (no workers, a resource it cannot load), the file is decoded on the
 * page's thread instead.
 */
import { AssetError } from '../scene/assetError';
import { decodeMesh } from '../scene/mesh';
import type { TriangleMesh } from '../scene/types';
import { companionResolver, recordResources, type FileTable } from './companionFiles';
import type { DecodeRequest, DecodeResponse } from './meshDecodeWorker';

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

export async function decodeMeshOffThread(bytes: Uint8Array, fileName: string, files: FileTable = new Map()): Promise<TriangleMesh> {
  if (typeof Worker === 'undefined') return decodeHere(bytes, fileName, files);
  worker ??= startWorker();
  const id = nextId++;
  const response = await new Promise<DecodeResponse | null>((resolve) => {
    pending.set(id, resolve);
    // A copy goes to the worker: the caller keeps its bytes for the fallback.
    worker!.postMessage({ id, bytes, fileName, files: new Map(files) } satisfies DecodeRequest);
  });
  if (response && 'mesh' in response) {
    recordResources(response.mesh, response.resources);
    return response.mesh;
  }
  if (response && response.assetError) throw new AssetError(response.error);
  return decodeHere(bytes, fileName, files);
}

async function decodeHere(bytes: Uint8Array, fileName: string, files: FileTable): Promise<TriangleMesh> {
  const companions = companionResolver(files, fileName);
  const mesh = await decodeMesh(bytes, fileName, { resolveResource: companions.resolve });
  recordResources(mesh, companions.read);
  return mesh;
}
