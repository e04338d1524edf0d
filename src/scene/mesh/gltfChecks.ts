/**
 * Checks of a glTF's JSON before glTF-Transform reads it, so that a broken
 * reference is reported by its place in the file (`materials[1].
 * normalTexture: texture 7 does not exist`) rather than as a reader's crash,
 * and the list of the extensions the renderer ignores.
 */
import { AssetError } from '../assetError';
import type { GltfJson } from './gltf';
import { READ_MATERIAL_EXTENSIONS } from './gltfMaterials';

/** Extensions read somewhere (materials, geometry, lights) or that change nothing the renderer draws. */
const READ_EXTENSIONS = new Set<string>([
  ...READ_MATERIAL_EXTENSIONS,
  'KHR_draco_mesh_compression',
  'KHR_mesh_quantization',
  'KHR_lights_punctual',
  'EXT_texture_webp',
]);

const TEXTURE_SLOTS: [string, string][] = [
  ['pbrMetallicRoughness', 'baseColorTexture'],
  ['pbrMetallicRoughness', 'metallicRoughnessTexture'],
  ['', 'normalTexture'],
  ['', 'emissiveTexture'],
  ['', 'occlusionTexture'],
  ['KHR_materials_transmission', 'transmissionTexture'],
  ['KHR_materials_clearcoat', 'clearcoatTexture'],
  ['KHR_materials_clearcoat', 'clearcoatRoughnessTexture'],
  ['KHR_materials_clearcoat', 'clearcoatNormalTexture'],
];

type Json = Record<string, unknown>;
const object = (value: unknown): Json | undefined => (typeof value === 'object' && value !== null && !Array.isArray(value) ? (value as Json) : undefined);

/** Throws naming the first texture or image reference that points nowhere, or a KTX2/Basis image. */
export function checkGltfReferences(json: GltfJson): void {
  if (json.extensionsUsed?.includes('KHR_texture_basisu')) {
    throw new AssetError('its textures are KTX2/Basis (KHR_texture_basisu), which this renderer cannot read: re-export the model with PNG or JPEG textures');
  }
  const textures = json.textures ?? [];
  const images = json.images ?? [];
  (json.materials ?? []).forEach((material, m) => {
    for (const [parent, slot] of TEXTURE_SLOTS) {
      const holder = parent === '' ? material : parent.startsWith('KHR_') ? object(object(material.extensions)?.[parent]) : object(material[parent]);
      const info = object(holder?.[slot]);
      if (!info) continue;
      const index = info.index;
      const where = `materials[${m}].${parent ? `${parent}.` : ''}${slot}`;
      if (!Number.isInteger(index) || (index as number) < 0 || (index as number) >= textures.length) {
        throw new AssetError(`${where}: texture ${JSON.stringify(index)} does not exist (the file has ${textures.length})`);
      }
    }
  });
  textures.forEach((texture, t) => {
    const source = texture.source ?? (object(texture.extensions?.EXT_texture_webp)?.source as number | undefined);
    if (source === undefined) return;
    if (!Number.isInteger(source) || source < 0 || source >= images.length) {
      throw new AssetError(`textures[${t}]: image ${JSON.stringify(source)} does not exist (the file has ${images.length})`);
    }
    if (images[source].mimeType === 'image/ktx2' || /\.ktx2$/i.test(images[source].uri ?? '')) {
      throw new AssetError(`images[${source}] is KTX2/Basis, which this renderer cannot read: re-export the model with PNG or JPEG textures`);
    }
  });
}

/** The extensions the file uses that the renderer does not read, sorted. */
export function ignoredExtensions(json: GltfJson): string[] {
  return [...new Set(json.extensionsUsed ?? [])].filter((name) => !READ_EXTENSIONS.has(name)).sort();
}
