/**
 * The files a model names beside itself (a `.gltf`'s `.bin` and images, an
 * OBJ's `.mtl`), found among the files the user opened or dropped with it.
 * Dropped files carry no folders, so a name is looked up as written
 * (relative to the model's folder) and then by its base name, as the page's
 * scene loader looks up every file (sceneLoader.ts). Each model's decoded
 * triangles remember which of these files they were read from, so the
 * autosave keeps them and the share link names them (userFiles).
 * Pure TypeScript: the page and the mesh decode Worker use it.
 */
import { materialTextures } from '../materials/registry';
import { AssetError } from '../scene/assetError';
import { fileImageName, joinPath } from '../scene/fileMaterials';
import type { TriangleMesh } from '../scene/types';
import { MAX_ASSET_BYTES } from './fileLimits';

/** The user's files opened or dropped together, by file name. */
export type FileTable = ReadonlyMap<string, Blob>;


export const baseName = (name: string) => name.slice(name.replace(/\\/g, '/').lastIndexOf('/') + 1);
const folderOf = (file: string) => file.slice(0, Math.max(0, file.replace(/\\/g, '/').lastIndexOf('/')));

/** The key of `name` in `files`: as written, else its base name; undefined when neither is there. */
export function fileKey(files: FileTable, name: string): string | undefined {
  if (files.has(name)) return name;
  const base = baseName(name);
  return files.has(base) ? base : undefined;
}

/** The bytes of a user file, refused from its size before it is read (the autosave keeps no larger file). */
export async function readUserFile(blob: Blob): Promise<Uint8Array> {
  if (blob.size > MAX_ASSET_BYTES) throw new AssetError(`the file is ${blob.size} bytes; the page takes files of at most ${MAX_ASSET_BYTES / 2 ** 20} MB`);
  return new Uint8Array(await blob.arrayBuffer());
}

const decodeUri = (uri: string) => {
  try {
    return decodeURIComponent(uri);
  } catch {
    return uri;
  }
};

/**
 * A resource resolver for decodeMesh that reads the files `meshFile` names
 * (URIs relative to it) from `files`, and the keys of the files it read.
 */
export function companionResolver(files: FileTable, meshFile: string): { resolve: (uri: string) => Promise<Uint8Array>; read: string[] } {
  const read: string[] = [];
  const resolve = async (uri: string) => {
    const name = joinPath(folderOf(meshFile), decodeUri(uri));
    const key = fileKey(files, name);
    if (key === undefined) throw new Error(`"${name}" was not opened with it: open or drop it together with the model`);
    const bytes = await readUserFile(files.get(key)!);
    if (!read.includes(key)) read.push(key);
    return bytes;
  };
  return { resolve, read };
}

const resources = new WeakMap<TriangleMesh, readonly string[]>();

/** Records the files beside it that a decoded model was read from. */
export function recordResources(data: TriangleMesh, names: readonly string[]): void {
  if (names.length > 0) resources.set(data, [...names]);
}

/**
 * The user files a model needs besides itself: the files it was read from
 * (.bin, .mtl) and the images beside it that its own materials name
 * (as the scene's assets name them: fileImageName).
 */
export function meshCompanions(meshFile: string, data: TriangleMesh | undefined): string[] {
  if (!data) return [];
  const images = (data.fileMaterials?.materials ?? []).flatMap((m) => materialTextures(m.material).map((t) => t.texture.image));
  const external = images.filter((image) => !image.startsWith('#')).map((image) => fileImageName(meshFile, image));
  return [...new Set([...(resources.get(data) ?? []), ...external])];
}
