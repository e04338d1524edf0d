/**
 * glTF materials as the format's principled material (scene-format.md,
 * "glTF materials": the mapping table and its departures from glTF), read
 * through glTF-Transform. Each texture becomes a texture object of the
 * format: its image named in the file's terms (`#N` for the file's embedded
 * texture N, else the URI relative to the file's folder), its
 * KHR_texture_transform as `uv`, the factor as `scale`. Pure TypeScript.
 */
import type { Document, Material as GltfMaterial, Texture as GltfTexture, TextureInfo } from '@gltf-transform/core';
import type { Clearcoat, EmissiveStrength, IOR, Transform, Transmission } from '@gltf-transform/extensions';
import { materialSchema, normalizeMaterial } from '../../materials/registry';
import { MAX_IOR, MIN_IOR } from '../../materials/kind';
import { AssetError } from '../assetError';
import type { FileMaterial } from '../types';

/** The extensions this mapping reads (the others a file uses are listed in a warning). */
export const READ_MATERIAL_EXTENSIONS = [
  'KHR_texture_transform',
  'KHR_materials_emissive_strength',
  'KHR_materials_ior',
  'KHR_materials_transmission',
  'KHR_materials_clearcoat',
] as const;

/** glTF's default material (no `material` on a primitive): white, fully metallic and rough, as the spec says. */
export const GLTF_DEFAULT_MATERIAL_JSON = { type: 'principled', baseColor: [1, 1, 1], metallic: 1, roughness: 1 } as const;

interface TextureRef {
  image: string;
  uv: { offset: [number, number]; scale: [number, number]; rotation: number };
  texCoord: number;
}

/** Maps one glTF material; `where` names it in messages (`materials[2] "Wood"`), `warn` collects what is approximated. */
export function mapGltfMaterial(document: Document, material: GltfMaterial, where: string, warn: (message: string) => void): FileMaterial {
  const textures = document.getRoot().listTextures();
  const texCoords = new Set<number>();
  const ref = (texture: GltfTexture | null, info: TextureInfo | null, slot: string): TextureRef | null => {
    if (!texture || !info) return null;
    const r = textureRef(textures.indexOf(texture), texture, info, `${where}.${slot}`);
    texCoords.add(r.texCoord);
    return r;
  };
  const json: Record<string, unknown> = { type: 'principled' };
  const pbr = material;
  const [r, g, b, alpha] = pbr.getBaseColorFactor();
  const baseColorTexture = ref(pbr.getBaseColorTexture(), pbr.getBaseColorTextureInfo(), 'baseColorTexture');
  json.baseColor = baseColorTexture ? textureJson(baseColorTexture, [r, g, b].map(clamp01)) : [r, g, b].map(clamp01);
  const mr = ref(pbr.getMetallicRoughnessTexture(), pbr.getMetallicRoughnessTextureInfo(), 'metallicRoughnessTexture');
  json.metallic = mr ? { ...textureJson(mr, clamp01(pbr.getMetallicFactor())), channel: 'b' } : clamp01(pbr.getMetallicFactor());
  json.roughness = mr ? { ...textureJson(mr, clamp01(pbr.getRoughnessFactor())), channel: 'g' } : clamp01(pbr.getRoughnessFactor());
  const normal = ref(pbr.getNormalTexture(), pbr.getNormalTextureInfo(), 'normalTexture');
  if (normal) json.normalMap = textureJson(normal, pbr.getNormalScale());
  const opacity = alphaOpacity(pbr, baseColorTexture, alpha);
  if (opacity !== 1) json.opacity = opacity;
  const emission = emissionJson(pbr, ref(pbr.getEmissiveTexture(), pbr.getEmissiveTextureInfo(), 'emissiveTexture'));
  if (emission) json.emission = emission;
  const ior = pbr.getExtension<IOR>('KHR_materials_ior')?.getIOR();
  if (ior !== undefined) json.ior = clampIor(ior, where, warn);
  const transmission = pbr.getExtension<Transmission>('KHR_materials_transmission');
  if (transmission) {
    const factor = clamp01(transmission.getTransmissionFactor());
    const t = ref(transmission.getTransmissionTexture(), transmission.getTransmissionTextureInfo(), 'KHR_materials_transmission.transmissionTexture');
    json.specTrans = t ? { ...textureJson(t, factor), channel: 'r' } : factor;
  }
  const coat = pbr.getExtension<Clearcoat>('KHR_materials_clearcoat');
  if (coat) {
    const factor = clamp01(coat.getClearcoatFactor());
    const t = ref(coat.getClearcoatTexture(), coat.getClearcoatTextureInfo(), 'KHR_materials_clearcoat.clearcoatTexture');
    json.clearcoat = t ? { ...textureJson(t, factor), channel: 'r' } : factor;
    json.clearcoatGloss = 1 - clamp01(coat.getClearcoatRoughnessFactor());
    if (coat.getClearcoatRoughnessTexture() || coat.getClearcoatNormalTexture()) warn(`${where}: the clear coat's roughness and normal textures are ignored (the coat is principled's)`);
  }
  const uvSet = chooseTexCoord(texCoords, where, warn);
  return { name: material.getName(), material: parseMaterial(json, where), uvSet, vertexColors: false };
}

/** A texture's reference: its image's name, transform and coordinate set (the transform's texCoord overrides the info's). */
function textureRef(index: number, texture: GltfTexture, info: TextureInfo, where: string): TextureRef {
  const mime = texture.getMimeType();
  if (mime === 'image/ktx2') throw new AssetError(`${where}: the image is KTX2/Basis (KHR_texture_basisu), which this renderer cannot read: re-export the model with PNG or JPEG textures`);
  const uri = texture.getURI();
  const image = uri && !uri.startsWith('data:') ? decodeUri(uri) : `#${index}`;
  const transform = info.getExtension<Transform>('KHR_texture_transform');
  const offset = (transform?.getOffset() ?? [0, 0]) as [number, number];
  const scale = (transform?.getScale() ?? [1, 1]) as [number, number];
  const rotation = ((transform?.getRotation() ?? 0) * 180) / Math.PI;
  const texCoord = transform?.getTexCoord() ?? info.getTexCoord();
  return { image, uv: { offset: [offset[0], offset[1]], scale: [scale[0], scale[1]], rotation }, texCoord };
}

const decodeUri = (uri: string) => {
  try {
    return decodeURIComponent(uri);
  } catch {
    return uri;
  }
};

const textureJson = (t: TextureRef, scale: number | number[]) => ({ image: t.image, scale, uv: t.uv });

/** alphaMode: OPAQUE 1; MASK the base color's alpha with cutoff (or the constant's verdict); BLEND the alpha itself. */
function alphaOpacity(m: GltfMaterial, texture: TextureRef | null, factor: number): number | Record<string, unknown> {
  const mode = m.getAlphaMode();
  const a = clamp01(factor);
  if (mode === 'MASK') {
    const cutoff = m.getAlphaCutoff();
    // The renderer thresholds the filtered texel, then scales: factor * alpha >= cutoff is alpha >= cutoff / factor.
    if (!texture) return a >= cutoff ? 1 : 0;
    if (cutoff <= 0) return 1; // every factor x alpha >= 0 passes, a zero factor included
    if (a === 0 || cutoff / a > 1) return 0;
    return { ...textureJson(texture, 1), channel: 'a', cutoff: cutoff / a };
  }
  if (mode === 'BLEND') return texture ? { ...textureJson(texture, a), channel: 'a' } : a;
  return 1;
}

/** emissiveFactor x emissiveTexture x KHR_materials_emissive_strength; none when black. */
function emissionJson(m: GltfMaterial, texture: TextureRef | null): Record<string, unknown> | null {
  const factor = m.getEmissiveFactor().map((c) => Math.max(0, c));
  const strength = Math.max(0, m.getExtension<EmissiveStrength>('KHR_materials_emissive_strength')?.getEmissiveStrength() ?? 1);
  if (strength === 0 || factor.every((c) => c === 0)) return null;
  return { color: texture ? textureJson(texture, factor) : factor, intensity: strength };
}

function clampIor(ior: number, where: string, warn: (message: string) => void): number {
  const clamped = Math.min(MAX_IOR, Math.max(MIN_IOR, ior));
  if (clamped !== ior) warn(`${where}: KHR_materials_ior ${ior} becomes ${clamped} (the format's ior is in [${MIN_IOR}, ${MAX_IOR}])`);
  return clamped;
}

/** The one coordinate set a material's textures read (the renderer gives a material one set). */
function chooseTexCoord(sets: Set<number>, where: string, warn: (message: string) => void): 0 | 1 {
  const used = [...sets].sort();
  if (used.some((s) => s > 1)) throw new AssetError(`${where}: a texture reads TEXCOORD_${Math.max(...used)}; only TEXCOORD_0 and TEXCOORD_1 are read`);
  if (used.length > 1) warn(`${where}: its textures read both TEXCOORD_0 and TEXCOORD_1; all of them read TEXCOORD_0 here`);
  return used.length === 1 ? (used[0] as 0 | 1) : 0;
}

/** Through the principled schema, so the material is exactly what the scene JSON would give. */
function parseMaterial(json: Record<string, unknown>, where: string) {
  const result = materialSchema('principled')!.safeParse(json);
  if (!result.success) {
    const issue = result.error.issues[0];
    throw new AssetError(`${where}: ${issue.path.join('.')}: ${issue.message}`);
  }
  return normalizeMaterial(result.data as Record<string, unknown>);
}

/** glTF's default material, for primitives without one. */
export function gltfDefaultMaterial(): FileMaterial {
  return { name: '(glTF default)', material: parseMaterial({ ...GLTF_DEFAULT_MATERIAL_JSON, baseColor: [1, 1, 1] }, 'the default material'), uvSet: 0, vertexColors: false };
}

const clamp01 = (x: number) => Math.min(1, Math.max(0, Number.isFinite(x) ? x : 0));
