/**
 * Web Worker: decodes a model file (decodeMesh) off the page's thread.
 * In: { id, bytes, fileName }; out: { id, mesh } (arrays transferred) or
 * { id, error, assetError } (assetError: the file itself was rejected).
 */
import { AssetError } from '../scene/assetError';
import { decodeMesh } from '../scene/mesh';
import type { TriangleMesh } from '../scene/types';

export type DecodeResponse = { id: number; mesh: TriangleMesh } | { id: number; error: string; assetError: boolean };

if ('WorkerGlobalScope' in globalThis && typeof document === 'undefined') {
  self.onmessage = async (event: MessageEvent<{ id: number; bytes: Uint8Array; fileName: string }>) => {
    const { id, bytes, fileName } = event.data;
    try {
      const mesh = await decodeMesh(bytes, fileName);
      const transfer = [mesh.positions, mesh.indices, mesh.normals, mesh.uvs, mesh.uvs1, mesh.tangents].filter((a) => a != null).map((a) => a.buffer as ArrayBuffer);
      self.postMessage({ id, mesh } satisfies DecodeResponse, { transfer: [...new Set(transfer)] });
    } catch (error) {
      self.postMessage({ id, error: (error as Error)?.message ?? String(error), assetError: error instanceof AssetError } satisfies DecodeResponse);
    }
  };
}
