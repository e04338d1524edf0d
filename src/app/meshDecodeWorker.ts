/**
 * Web Worker: decodes a model file (decodeMesh) off the page's thread.
 * In: { id, bytes, fileName, files } (files: the user's files opened with
 * it, which a .gltf's .bin or an OBJ's .mtl is read from); out: { id, mesh,
 * resources } (arrays transferred; resources: the keys of the files read)
 * or { id, error, assetError } (assetError: the file itself was rejected).
 */
import { AssetError } from '../scene/assetError';
import { decodeMesh } from '../scene/mesh';
import type { TriangleMesh } from '../scene/types';
import { companionResolver, type FileTable } from './companionFiles';

export type DecodeRequest = { id: number; bytes: Uint8Array; fileName: string; files: FileTable };
export type DecodeResponse = { id: number; mesh: TriangleMesh; resources: string[] } | { id: number; error: string; assetError: boolean };

if ('WorkerGlobalScope' in globalThis && typeof document === 'undefined') {
  self.onmessage = async (event: MessageEvent<DecodeRequest>) => {
    const { id, bytes, fileName, files } = event.data;
    try {
      const companions = companionResolver(files, fileName);
      const mesh = await decodeMesh(bytes, fileName, { resolveResource: companions.resolve });
      const transfer = [mesh.positions, mesh.indices, mesh.normals, mesh.uvs, mesh.uvs1, mesh.tangents].filter((a) => a != null).map((a) => a.buffer as ArrayBuffer);
      self.postMessage({ id, mesh, resources: companions.read } satisfies DecodeResponse, { transfer: [...new Set(transfer)] });
    } catch (error) {
      self.postMessage({ id, error: (error as Error)?.message ?? String(error), assetError: error instanceof AssetError } satisfies DecodeResponse);
    }
  };
}
