/**
 * Mesh files to TriangleMesh: `decodeMesh` picks the decoder by extension.
 * Every decoder throws AssetError (without the scene path; the caller
 * prefixes `meshes[i].file: `) for a file it cannot accept: unreadable or
 * corrupt, no triangles, a non-finite vertex, an out-of-range index, a header
 * that promises more data than there is. Degenerate (zero-area) triangles
 * are dropped (finalize.ts). Pure TypeScript: Node and the browser.
 */
import { AssetError } from '../assetError';
import type { TriangleMesh } from '../types';
import { decodeGltf, type ResourceResolver } from './gltf';
import { decodeObj } from './obj';
import { decodePly } from './ply';

export type { ResourceResolver } from './gltf';
export { encodePly } from './plyEncode';
export { meshToWorldMatrix, transformMesh, applyMatrix, applyMatrixToTangents, inverseAffine, type MeshTransform } from './transform';
export { meshTangents } from './tangents';

export const MESH_EXTENSIONS = ['.obj', '.ply', '.gltf', '.glb'] as const;

export interface DecodeMeshOptions {
  /**
   * Reads a file beside the mesh by its URI (relative to the mesh file's folder, percent-encoded): a `.gltf`'s
   * external buffers (without it such files are rejected) and an OBJ's MTL files (without it, or when one cannot be
   * read, the OBJ loads with a warning and the default material).
   */
  resolveResource?: ResourceResolver;
}

export async function decodeMesh(bytes: Uint8Array, fileName: string, options: DecodeMeshOptions = {}): Promise<TriangleMesh> {
  const extension = /\.[^./\\]+$/.exec(fileName.toLowerCase())?.[0] ?? '';
  if (bytes.length === 0) throw new AssetError('the file is empty');
  switch (extension) {
    case '.obj': return decodeObj(bytes, options.resolveResource);
    case '.ply': return decodePly(bytes);
    case '.gltf': return decodeGltf(bytes, false, options.resolveResource);
    case '.glb': return decodeGltf(bytes, true);
    default: throw new AssetError(`unsupported mesh file type "${extension || fileName}" (use ${MESH_EXTENSIONS.join(', ')})`);
  }
}
