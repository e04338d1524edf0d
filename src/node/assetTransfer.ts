/**
 * Decoded scene assets (SceneAssets: environment maps, meshes) as one block
 * of bytes and a small JSON manifest, so the headless page gets the arrays
 * Node decoded instead of decoding the files again: the session serves the
 * block (StaticServer.publish) and the page fetches it as an ArrayBuffer,
 * far faster than typed arrays through Playwright's evaluate (JSON).
 *
 * Every typed array in an asset, at any depth, goes into the block; every
 * other value (sizes, nulls) into the manifest, so a field added to
 * TriangleMesh or EnvironmentImage crosses without a change here. Pure (no
 * Node or DOM API): the page bundles it too.
 */
import type { SceneAssets } from '../scene/assets';
import type { TextureImage } from '../scene/texture/image';
import type { EnvironmentImage, TriangleMesh } from '../scene/types';

const ARRAY_TYPES = {
  Float32Array,
  Float64Array,
  Int8Array,
  Int16Array,
  Int32Array,
  Uint8Array,
  Uint8ClampedArray,
  Uint16Array,
  Uint32Array,
} as const;
type ArrayType = keyof typeof ARRAY_TYPES;

/** A typed array in the block: its type, byte offset and element count. */
export interface ArrayRef {
  $array: ArrayType;
  offset: number;
  length: number;
}

export interface AssetManifest {
  /** Where the page fetches the block, relative to the page. */
  url: string;
  /** Total bytes of the block (the page checks it). */
  byteLength: number;
  /** By name as written in the scene; typed arrays replaced by ArrayRefs. */
  maps: [string, unknown][];
  meshes: [string, unknown][];
  images: [string, unknown][];
  encodedImages?: [string, unknown][];
}

/** Whether there is anything to transfer. */
export function hasAssets(assets: SceneAssets | undefined): assets is SceneAssets {
  return !!assets && (assets.maps.size > 0 || assets.meshes.size > 0 || (assets.images?.size ?? 0) > 0 || (assets.encodedImages?.size ?? 0) > 0);
}

/** The block and its manifest (`url` left empty for the caller to fill in). */
export function packAssets(assets: SceneAssets): { manifest: AssetManifest; bytes: Uint8Array } {
  const arrays: { view: ArrayBufferView; offset: number }[] = [];
  let byteLength = 0;
  const encode = (value: unknown): unknown => {
    if (ArrayBuffer.isView(value) && !(value instanceof DataView)) {
      const type = (Object.keys(ARRAY_TYPES) as ArrayType[]).find((t) => value instanceof ARRAY_TYPES[t]);
      if (!type) throw new Error(`cannot transfer a ${value.constructor.name}`);
      byteLength = Math.ceil(byteLength / 8) * 8; // aligned for any element size
      const ref: ArrayRef = { $array: type, offset: byteLength, length: (value as Float32Array).length };
      arrays.push({ view: value, offset: byteLength });
      byteLength += value.byteLength;
      return ref;
    }
    if (Array.isArray(value)) return value.map(encode);
    // A mesh's file materials hold their embedded images in a Map.
    if (value instanceof Map) return { $map: [...value].map(([k, v]) => [k, encode(v)]) };
    if (value !== null && typeof value === 'object') return Object.fromEntries(Object.entries(value).map(([k, v]) => [k, encode(v)]));
    return value;
  };
  const maps = [...assets.maps].map(([name, map]): [string, unknown] => [name, encode(map)]);
  const meshes = [...assets.meshes].map(([name, mesh]): [string, unknown] => [name, encode(mesh)]);
  const images = [...(assets.images ?? [])].map(([name, image]): [string, unknown] => [name, encode(image)]);
  const encodedImages = [...(assets.encodedImages ?? [])].map(([name, bytes]): [string, unknown] => [name, encode(bytes)]);
  const bytes = new Uint8Array(byteLength);
  for (const { view, offset } of arrays) bytes.set(new Uint8Array(view.buffer, view.byteOffset, view.byteLength), offset);
  return { manifest: { url: '', byteLength, maps, meshes, images, ...(encodedImages.length > 0 ? { encodedImages } : {}) }, bytes };
}

/**
 * The assets back from the block. Each array is a copy of its own (not a
 * view of the block), so handing one to a worker cannot detach the others.
 */
export function unpackAssets(manifest: AssetManifest, block: ArrayBuffer): SceneAssets {
  if (block.byteLength !== manifest.byteLength) throw new Error(`asset block has ${block.byteLength} bytes, expected ${manifest.byteLength}`);
  const decode = (value: unknown): unknown => {
    if (Array.isArray(value)) return value.map(decode);
    if (value === null || typeof value !== 'object') return value;
    if ('$map' in value) return new Map((value as { $map: [string, unknown][] }).$map.map(([k, v]) => [k, decode(v)]));
    if ('$array' in value) {
      const { $array, offset, length } = value as ArrayRef;
      const type = ARRAY_TYPES[$array];
      return new type(block.slice(offset, offset + length * type.BYTES_PER_ELEMENT));
    }
    return Object.fromEntries(Object.entries(value).map(([k, v]) => [k, decode(v)]));
  };
  return {
    maps: new Map(manifest.maps.map(([name, map]) => [name, decode(map) as EnvironmentImage])),
    meshes: new Map(manifest.meshes.map(([name, mesh]) => [name, decode(mesh) as TriangleMesh])),
    images: new Map((manifest.images ?? []).map(([name, image]) => [name, decode(image) as TextureImage])),
    ...(manifest.encodedImages ? { encodedImages: new Map(manifest.encodedImages.map(([name, bytes]) => [name, decode(bytes) as Uint8Array])) } : {}),
  };
}
