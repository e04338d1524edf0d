/**
 * Reading a file the CLI was given, with its size checked first: a file
 * above MAX_MESH_FILE_BYTES (a 2 GB model) is refused from its size, before
 * any of it is read. No decoder is imported here, so the CLI starts fast.
 */
import { readFile, stat } from 'node:fs/promises';
import { AssetError } from '../scene/assetError';
import { MAX_MESH_FILE_BYTES } from '../scene/limits';

/** A file's bytes; AssetError, without reading it, when it is larger than MAX_MESH_FILE_BYTES. */
export async function readFileWithinLimit(path: string): Promise<Uint8Array> {
  const { size } = await stat(path);
  if (size > MAX_MESH_FILE_BYTES) {
    throw new AssetError(`the file is ${size} bytes; files above ${MAX_MESH_FILE_BYTES / 2 ** 30} GiB (MAX_MESH_FILE_BYTES) are not read`);
  }
  return new Uint8Array(await readFile(path));
}
