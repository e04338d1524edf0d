/**
 * Reads a mesh file from disk for the CLI: the file's bytes through
 * decodeMesh, with a `.gltf`'s external buffers resolved relative to the
 * file's folder (URI-decoded, as glTF URIs are). An unreadable file is an
 * AssetError like any other bad file, so the caller can prefix
 * `meshes[i].file: `. Files above MAX_MESH_FILE_BYTES are refused from
 * their size, before they are read.
 */
import { dirname, resolve } from 'node:path';
import { AssetError } from '../scene/assetError';
import { decodeMesh } from '../scene/mesh';
import type { TriangleMesh } from '../scene/types';
import { readFileWithinLimit } from './readWithinLimit';

export async function readMeshFile(path: string): Promise<TriangleMesh> {
  let bytes: Uint8Array;
  try {
    bytes = await readFileWithinLimit(path);
  } catch (error) {
    if (error instanceof AssetError) throw error;
    throw new AssetError(`cannot read ${path}: ${(error as NodeJS.ErrnoException).code ?? (error as Error).message}`);
  }
  const folder = dirname(path);
  return decodeMesh(bytes, path, {
    resolveResource: async (uri) => readFileWithinLimit(resolve(folder, decodeURIComponent(uri))),
  });
}
