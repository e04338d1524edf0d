/**
 * glTF materials, lights and bad inputs (scene-format.md "Meshes in version
 * 3", "glTF materials", "Textures", "Lights in version 3"), on models made
 * here with glTF-Transform: each texture's KHR_texture_transform as its own
 * `uv`, TEXCOORD_1, a mirroring node with TANGENT, alphaMode, COLOR_0, the
 * material extensions, ignored extensions, KHR_lights_punctual, every bad
 * input's message, and panels.glb end to end through loadSceneAssets and
 * resolveFileMaterials.
 */
import { mkdtempSync, readFileSync, rmSync, truncateSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { Document, WebIO, type Material as GltfMaterial, type Node, type Texture as GltfTexture, type TextureInfo } from '@gltf-transform/core';
import {
  KHRONOS_EXTENSIONS,
  KHRLightsPunctual,
  KHRMaterialsClearcoat,
  KHRMaterialsEmissiveStrength,
  KHRMaterialsIOR,
  KHRMaterialsSheen,
  KHRMaterialsTransmission,
  KHRTextureBasisu,
  KHRTextureTransform,
} from '@gltf-transform/extensions';
import { afterAll, describe, expect, it, vi } from 'vitest';
import { encodePng } from '../../src/cli/png';
import { materialSchema, normalizeMaterial, type PrincipledMaterial } from '../../src/materials/registry';
import { readMeshFile } from '../../src/node/readMesh';
import { readSceneFiles } from '../../src/node/sceneFiles';
import { loadSceneAssets, type SceneAssets } from '../../src/scene/assets';
import { resolveFileMaterials } from '../../src/scene/fileMaterials';
import { decodeMesh } from '../../src/scene/mesh';
import { SceneError, parseScene } from '../../src/scene/schema';
import { transformUv } from '../../src/scene/texture/bitmapLookup';
import type { Texture } from '../../src/scene/texture/texture';
import type { TriangleMesh } from '../../src/scene/types';

// The Draco decoder's WebAssembly refused, as in a page whose CSP lacks 'wasm-unsafe-eval' (only the Draco test decodes Draco).
vi.mock('draco3dgltf', () => ({
  default: { createDecoderModule: () => Promise.reject(new Error("WebAssembly.instantiate(): Refused to compile or instantiate WebAssembly module because 'wasm-unsafe-eval' is not allowed")) },
}));

type V3 = [number, number, number];
const FIXTURES = new URL('../fixtures/', import.meta.url);
const DEG = 180 / Math.PI;
const PNG = new Uint8Array(encodePng(2, 2, new Uint8Array(16).fill(200)));
const camera = { position: [0, 1, 5], target: [0, 0, 0] };
const io = () => new WebIO().registerExtensions(KHRONOS_EXTENSIONS);
const principled = (keys: Record<string, unknown>): PrincipledMaterial =>
  normalizeMaterial(materialSchema('principled')!.parse({ type: 'principled', ...keys }) as Record<string, unknown>) as PrincipledMaterial;
const sub = (a: readonly number[], b: readonly number[]): V3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a: readonly number[], b: readonly number[]) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a: readonly number[], b: readonly number[]): V3 => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const unit = (a: readonly number[]): V3 => {
  const l = Math.hypot(a[0], a[1], a[2]);
  return [a[0] / l, a[1] / l, a[2] / l];
};
const expectClose = (actual: ArrayLike<number>, expected: ArrayLike<number>, digits = 6) => {
  expect(actual.length).toBe(expected.length);
  for (let i = 0; i < expected.length; i++) expect(actual[i]).toBeCloseTo(expected[i], digits);
};

interface QuadOptions {
  material?: GltfMaterial | null;
  x0?: number;
  uv1?: number[];
  tangent?: number[];
  color?: { type: 'VEC3' | 'VEC4'; array: Float32Array<ArrayBuffer> | Uint8Array<ArrayBuffer> | Uint16Array<ArrayBuffer>; normalized?: boolean };
  indices?: number[];
  parent?: Node;
}

/** A document whose quads (z = 0, normal +z, TEXCOORD_0 (0,0) top-left) each have a mesh and a node of their own. */
function model() {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const scene = doc.createScene('scene');
  doc.getRoot().setDefaultScene(scene);
  const accessor = (type: 'SCALAR' | 'VEC2' | 'VEC3' | 'VEC4', array: Float32Array<ArrayBuffer> | Uint8Array<ArrayBuffer> | Uint16Array<ArrayBuffer>, normalized = false) =>
    doc.createAccessor().setType(type).setArray(array).setBuffer(buffer).setNormalized(normalized);
  const quad = (options: QuadOptions = {}) => {
    const x0 = options.x0 ?? 0;
    const primitive = doc.createPrimitive()
      .setAttribute('POSITION', accessor('VEC3', Float32Array.from([x0, 1, 0, x0, 0, 0, x0 + 1, 0, 0, x0 + 1, 1, 0])))
      .setAttribute('NORMAL', accessor('VEC3', Float32Array.from([0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1])))
      .setAttribute('TEXCOORD_0', accessor('VEC2', Float32Array.from([0, 0, 0, 1, 1, 1, 1, 0])))
      .setIndices(accessor('SCALAR', Uint16Array.from(options.indices ?? [0, 1, 2, 0, 2, 3])));
    if (options.uv1) primitive.setAttribute('TEXCOORD_1', accessor('VEC2', Float32Array.from(options.uv1)));
    if (options.tangent) primitive.setAttribute('TANGENT', accessor('VEC4', Float32Array.from([0, 1, 2, 3].flatMap(() => options.tangent!))));
    if (options.color) primitive.setAttribute('COLOR_0', accessor(options.color.type, options.color.array, options.color.normalized));
    if (options.material) primitive.setMaterial(options.material);
    const node = doc.createNode().setMesh(doc.createMesh().addPrimitive(primitive));
    (options.parent ?? scene).addChild(node);
    return node;
  };
  const texture = (name: string) => doc.createTexture(name).setImage(PNG).setMimeType('image/png');
  const transform = (info: TextureInfo | null, t: { offset?: [number, number]; rotation?: number; scale?: [number, number]; texCoord?: number }) => {
    const ext = doc.createExtension(KHRTextureTransform).createTransform();
    if (t.offset) ext.setOffset(t.offset);
    if (t.rotation !== undefined) ext.setRotation(t.rotation);
    if (t.scale) ext.setScale(t.scale);
    if (t.texCoord !== undefined) ext.setTexCoord(t.texCoord);
    info!.setExtension('KHR_texture_transform', ext);
  };
  return { doc, scene, quad, texture, transform };
}

const glb = (doc: Document) => io().writeBinary(doc);
const decodeDoc = async (doc: Document) => decodeMesh(await glb(doc), 'm.glb');
const materialsOf = (mesh: TriangleMesh) => mesh.fileMaterials!.materials.map((m) => m.material as PrincipledMaterial);

/** The document as .gltf JSON with its buffer embedded (a data: URI), after `edit`; images stay external unless `embedImages`. */
async function gltfJson(doc: Document, edit: (json: Record<string, any>) => void = () => {}, embedImages = true) {
  const { json, resources } = await io().writeJSON(doc);
  const dataUri = (uri: string) => `data:application/octet-stream;base64,${Buffer.from(resources[uri]).toString('base64')}`;
  for (const buffer of json.buffers ?? []) if (buffer.uri) buffer.uri = dataUri(buffer.uri);
  if (embedImages) for (const image of json.images ?? []) if (image.uri) image.uri = dataUri(image.uri);
  edit(json as Record<string, any>);
  return { bytes: new TextEncoder().encode(JSON.stringify(json)), resources };
}
const decodeJson = async (doc: Document, edit?: (json: Record<string, any>) => void) => decodeMesh((await gltfJson(doc, edit)).bytes, 'm.gltf');

/** glTF's KHR_texture_transform as its JSON example applies it (radians): T * R * S * uv. */
function gltfTransform(uv: [number, number], t: { offset: [number, number]; rotation: number; scale: [number, number] }): [number, number] {
  const [su, sv] = [uv[0] * t.scale[0], uv[1] * t.scale[1]];
  const [c, s] = [Math.cos(t.rotation), Math.sin(t.rotation)];
  return [t.offset[0] + c * su + s * sv, t.offset[1] - s * su + c * sv];
}

describe('KHR_texture_transform: each texture its own uv', () => {
  const transforms = {
    base: { offset: [0.1, 0.2] as [number, number], rotation: 0.5, scale: [2, 3] as [number, number] },
    mr: { offset: [0.3, 0] as [number, number], rotation: 0, scale: [1, 0.5] as [number, number] },
    normal: { offset: [0, 0] as [number, number], rotation: -1, scale: [4, 4] as [number, number] },
    emissive: { offset: [0, 0.7] as [number, number], rotation: Math.PI / 2, scale: [1, 1] as [number, number] },
  };

  it('baseColor, metallicRoughness, normal and emissive keep their own offset, scale and rotation (radians to degrees)', async () => {
    const { doc, quad, texture, transform } = model();
    const m = doc.createMaterial('four')
      .setBaseColorTexture(texture('base')).setMetallicRoughnessTexture(texture('mr')).setNormalTexture(texture('normal')).setNormalScale(0.7)
      .setEmissiveTexture(texture('emissive')).setEmissiveFactor([1, 0.5, 0.25]).setMetallicFactor(0.4).setRoughnessFactor(0.6);
    transform(m.getBaseColorTextureInfo(), transforms.base);
    transform(m.getMetallicRoughnessTextureInfo(), transforms.mr);
    transform(m.getNormalTextureInfo(), transforms.normal);
    transform(m.getEmissiveTextureInfo(), transforms.emissive);
    quad({ material: m });
    const mesh = await decodeDoc(doc);
    expect(mesh.warnings).toBeUndefined();
    const [material] = materialsOf(mesh);
    const slots: [Texture, keyof typeof transforms, string][] = [
      [material.baseColor as Texture, 'base', '#0'],
      [material.metallic as Texture, 'mr', '#1'],
      [material.roughness as Texture, 'mr', '#1'],
      [material.normalMap!, 'normal', '#2'],
      [material.emission!.texture!, 'emissive', '#3'],
    ];
    for (const [t, key, image] of slots) {
      const g = transforms[key];
      expect(t.image).toBe(image);
      expect(t.uv.offset).toEqual(g.offset);
      expect(t.uv.scale).toEqual(g.scale);
      expect(t.uv.rotation).toBeCloseTo(g.rotation * DEG, 10);
      // The format's lookup of that uv is glTF's transform of the coordinates.
      for (const uv of [[0.25, 0.75], [1, 0], [-0.5, 2]] as [number, number][]) expectClose(transformUv(uv, t.uv), gltfTransform(uv, g), 10);
    }
    expect((material.metallic as Texture).channel).toBe('b');
    expect((material.roughness as Texture).channel).toBe('g');
    expect([(material.metallic as Texture).scale, (material.roughness as Texture).scale]).toEqual([0.4, 0.6]);
    expect(material.normalMap!.scale).toBe(0.7);
    expect(material.emission!.color).toEqual([1, 0.5, 0.25]);
    expect(mesh.fileMaterials!.materials[0].uvSet).toBe(0);
  });

  it("the transform's texCoord overrides the texture info's", async () => {
    const { doc, quad, texture, transform } = model();
    const toOne = doc.createMaterial('to1').setBaseColorTexture(texture('a'));
    transform(toOne.getBaseColorTextureInfo(), { texCoord: 1 });
    const toZero = doc.createMaterial('to0').setBaseColorTexture(texture('b'));
    toZero.getBaseColorTextureInfo()!.setTexCoord(1);
    transform(toZero.getBaseColorTextureInfo(), { texCoord: 0, rotation: 0.1 });
    const uv1 = [0.5, 0.5, 0.5, 0.6, 0.6, 0.6, 0.6, 0.5];
    quad({ material: toOne, uv1 });
    quad({ material: toZero, uv1, x0: 2 });
    const mesh = await decodeDoc(doc);
    expect(mesh.fileMaterials!.materials.slice(0, 2).map((m) => m.uvSet)).toEqual([1, 0]);
  });

  it('textures of one material reading both sets: all read TEXCOORD_0, with a warning naming the material', async () => {
    const { doc, quad, texture } = model();
    const m = doc.createMaterial('mixed').setBaseColorTexture(texture('a')).setEmissiveTexture(texture('b')).setEmissiveFactor([1, 1, 1]);
    m.getEmissiveTextureInfo()!.setTexCoord(1);
    quad({ material: m, uv1: [0, 0, 0, 1, 1, 1, 1, 0] });
    const mesh = await decodeDoc(doc);
    expect(mesh.fileMaterials!.materials[0].uvSet).toBe(0);
    expect(mesh.warnings).toEqual([expect.stringMatching(/materials\[0\] "mixed": its textures read both TEXCOORD_0 and TEXCOORD_1/)]);
  });
});

describe('TEXCOORD_1', () => {
  it('a material whose textures read set 1 has uvSet 1, and its resolved mesh reads the file\'s TEXCOORD_1 as uvs', async () => {
    const { doc, quad, texture } = model();
    const one = doc.createMaterial('one').setBaseColorTexture(texture('a')).setMetallicRoughnessTexture(texture('b'));
    one.getBaseColorTextureInfo()!.setTexCoord(1);
    one.getMetallicRoughnessTextureInfo()!.setTexCoord(1);
    const zero = doc.createMaterial('zero').setBaseColorTexture(texture('c'));
    const uv1 = [0.1, 0.9, 0.2, 0.8, 0.3, 0.7, 0.4, 0.6];
    quad({ material: one, uv1 });
    quad({ material: zero, uv1, x0: 2 });
    const mesh = await decodeDoc(doc);
    expect(mesh.fileMaterials!.materials.map((m) => m.uvSet)).toEqual([1, 0, 0]);
    const scene = parseScene({ version: 3, camera, meshes: [{ file: 'm.glb' }] });
    const assets: SceneAssets = { maps: new Map(), meshes: new Map([['m.glb', mesh]]), images: new Map() };
    const resolved = resolveFileMaterials(scene, assets);
    expect(resolved.scene.meshes.map((m) => m.file)).toEqual(['m.glb#material0', 'm.glb#material1']);
    // Each vertex's coordinates by its position: the quad's corners (x0, 1), (x0, 0), (x0 + 1, 0), (x0 + 1, 1).
    const expectUvs = (subset: TriangleMesh, x0: number, uvs: number[]) => {
      const corners = [[x0, 1], [x0, 0], [x0 + 1, 0], [x0 + 1, 1]];
      expect(subset.positions.length / 3).toBe(4);
      for (let v = 0; v < 4; v++) {
        const corner = corners.findIndex(([x, y]) => x === subset.positions[v * 3] && y === subset.positions[v * 3 + 1]);
        expect([subset.uvs![v * 2], subset.uvs![v * 2 + 1]]).toEqual([Math.fround(uvs[corner * 2]), Math.fround(uvs[corner * 2 + 1])]);
      }
    };
    expectUvs(resolved.assets.meshes.get('m.glb#material0')!, 0, uv1);
    expectUvs(resolved.assets.meshes.get('m.glb#material1')!, 2, [0, 0, 0, 1, 1, 1, 1, 0]);
  });

  it('a primitive without the set its material reads is an error naming the primitive and the material', async () => {
    const { doc, quad, texture } = model();
    const one = doc.createMaterial('one').setBaseColorTexture(texture('a'));
    one.getBaseColorTextureInfo()!.setTexCoord(1);
    quad({ material: one });
    await expect(decodeDoc(doc)).rejects.toThrow(/meshes\[0\]\.primitives\[0\] has no TEXCOORD_1, which its material "one" needs/);
  });
});

describe('a mirroring node with TANGENT', () => {
  const rotation: [number, number, number, number] = [...unit([0.3, -0.5, 0.2]).map((c) => c * Math.sin(0.6)), Math.cos(0.6)] as [number, number, number, number];
  const cases: [string, V3][] = [['scale (-1, 1, 1)', [-1, 1, 1]], ['non-uniform scale (-2, 1, 0.5)', [-2, 1, 0.5]], ['scale (1, -3, 1)', [1, -3, 1]]];
  for (const [name, scale] of cases) {
    it(`${name} under a rotation: normals and tangents transformed, the bitangent the transformed one, the winding flipped back`, async () => {
      const { doc, quad } = model();
      // Local frame: n = +z, t = +x, w = 1: bitangent cross(n, t) * w = +y, up the image (v decreases along +y).
      const node = quad({ tangent: [1, 0, 0, 1] }).setScale(scale).setRotation(rotation).setTranslation([1, 2, 3]);
      const m = node.getWorldMatrix();
      const mat = (v: readonly number[]): V3 => [m[0] * v[0] + m[4] * v[1] + m[8] * v[2], m[1] * v[0] + m[5] * v[1] + m[9] * v[2], m[2] * v[0] + m[6] * v[1] + m[10] * v[2]];
      // The inverse transpose maps n = cross(x, y) to cross(M x, M y) / det(M): with det < 0, against cross(M x, M y).
      const det = dot(mat([1, 0, 0]), cross(mat([0, 1, 0]), mat([0, 0, 1])));
      expect(det).toBeLessThan(0);
      const expectedNormal = unit(cross(mat([1, 0, 0]), mat([0, 1, 0])).map((c) => -c));
      const expectedTangent = unit(mat([1, 0, 0]));
      const expectedBitangent = unit(mat([0, 1, 0]));
      const mesh = await decodeDoc(doc);
      const count = mesh.positions.length / 3;
      for (let v = 0; v < count; v++) {
        const n = [...mesh.normals!.subarray(v * 3, v * 3 + 3)];
        const t = [...mesh.tangents!.subarray(v * 4, v * 4 + 4)];
        expectClose(n, expectedNormal, 5);
        expectClose(t.slice(0, 3), expectedTangent, 5);
        expect(t[3]).toBe(-1); // w flips with the determinant's sign
        // glTF's formula on the transformed frame gives the transformed bitangent's direction (within the plane).
        const b = cross(n, t).map((c) => c * t[3]);
        expect(dot(unit(b), expectedBitangent)).toBeGreaterThan(scale.every((s) => Math.abs(s) === 1) ? 1 - 1e-5 : 0.3);
        expect(Math.abs(dot(b, n))).toBeLessThan(1e-5);
      }
      for (let i = 0; i < mesh.indices.length; i += 3) {
        const p = (k: number) => [...mesh.positions.subarray(mesh.indices[i + k] * 3, mesh.indices[i + k] * 3 + 3)];
        const face = unit(cross(sub(p(1), p(0)), sub(p(2), p(0))));
        expect(dot(face, expectedNormal)).toBeGreaterThan(1 - 1e-5); // winding agrees with the normal again
      }
    });
  }
});

describe('alphaMode', () => {
  const alphaModel = async (mode: 'OPAQUE' | 'MASK' | 'BLEND', alpha: number, textured: boolean, cutoff?: number) => {
    const { doc, quad, texture } = model();
    const m = doc.createMaterial('a').setAlphaMode(mode).setBaseColorFactor([0.5, 0.6, 0.7, alpha]);
    if (cutoff !== undefined) m.setAlphaCutoff(cutoff);
    if (textured) m.setBaseColorTexture(texture('alpha'));
    quad({ material: m });
    return materialsOf(await decodeDoc(doc))[0];
  };
  /** The opacity the renderer gives a texel of alpha `texel`: threshold at cutoff, then scale (scene-format "Textures"). */
  const opacityAt = (opacity: number | Texture, texel: number) => {
    if (typeof opacity === 'number') return opacity;
    const value = opacity.cutoff === undefined ? texel : texel >= opacity.cutoff ? 1 : 0;
    return value * (opacity.scale as number);
  };

  it('MASK with a texture: alpha channel, cutoff / factor, so that factor x alpha >= cutoff is opaque, at the cut-off included', async () => {
    for (const [factor, cutoff] of [[0.8, 0.4], [1, 0.5], [0.5, 0.25], [0.6, 0.3]]) {
      const material = await alphaModel('MASK', factor, true, cutoff);
      const opacity = material.opacity as Texture;
      expect(opacity).toMatchObject({ image: '#0', channel: 'a', scale: 1 });
      for (const texel of [0, 0.1, 0.3, 0.49, 0.5, 0.51, 0.75, 1]) {
        expect(opacityAt(opacity, texel), `factor ${factor} cutoff ${cutoff} texel ${texel}`).toBe(factor * texel >= cutoff ? 1 : 0);
      }
    }
  });

  it('MASK: the default cutoff is 0.5; a factor below the cutoff is transparent everywhere (a constant 0)', async () => {
    expect(((await alphaModel('MASK', 1, true)).opacity as Texture).cutoff).toBe(0.5);
    expect((await alphaModel('MASK', 0.4, true, 0.5)).opacity).toBe(0);
    expect((await alphaModel('MASK', 0, true, 0.5)).opacity).toBe(0);
  });

  it('MASK with cutoff 0: everything passes (factor x alpha >= 0), a zero factor included', async () => {
    for (const factor of [0, 0.5, 1]) {
      const opacity = (await alphaModel('MASK', factor, true, 0)).opacity;
      for (const texel of [0, 0.5, 1]) expect(opacityAt(opacity, texel)).toBe(1);
    }
    expect((await alphaModel('MASK', 0, false, 0)).opacity).toBe(1);
  });

  it('MASK without a texture: the constant alpha against the cutoff (equal is opaque)', async () => {
    expect((await alphaModel('MASK', 0.6, false, 0.5)).opacity).toBe(1);
    expect((await alphaModel('MASK', 0.5, false, 0.5)).opacity).toBe(1);
    expect((await alphaModel('MASK', 0.4, false, 0.5)).opacity).toBe(0);
  });

  it('BLEND: opacity = alpha (the texture\'s alpha times the factor); OPAQUE: 1 whatever the alpha', async () => {
    expect((await alphaModel('BLEND', 0.3, false)).opacity).toBeCloseTo(0.3, 6);
    const blended = (await alphaModel('BLEND', 0.7, true)).opacity as Texture;
    expect(blended).toMatchObject({ image: '#0', channel: 'a' });
    expect(blended.scale).toBeCloseTo(0.7, 6);
    expect(blended.cutoff).toBeUndefined();
    expect((await alphaModel('OPAQUE', 0.3, true)).opacity).toBe(1);
    expect((await alphaModel('OPAQUE', 0.3, false)).opacity).toBe(1);
  });
});

describe('COLOR_0', () => {
  it('VEC3 float, VEC4 normalized unsigned byte and short: linear RGB per vertex; a primitive without it is white', async () => {
    const { doc, quad } = model();
    const material = doc.createMaterial('m');
    const float3 = [0.2, 0.4, 0.6, 0.1, 0.3, 0.5, 1, 0, 0.25, 0, 0.5, 1];
    quad({ material, color: { type: 'VEC3', array: Float32Array.from(float3) } });
    quad({ material, x0: 2, color: { type: 'VEC4', array: Uint8Array.from([255, 128, 0, 255, 0, 51, 255, 10, 255, 255, 255, 0, 1, 2, 3, 4]), normalized: true } });
    quad({ material, x0: 4, color: { type: 'VEC4', array: Uint16Array.from([65535, 32768, 0, 65535, 0, 13107, 65535, 1, 65535, 65535, 65535, 0, 1, 2, 3, 4]), normalized: true } });
    quad({ material, x0: 6 });
    const mesh = await decodeDoc(doc);
    const byCorner = new Map<string, number[]>();
    for (let v = 0; v < mesh.positions.length / 3; v++) byCorner.set(`${mesh.positions[v * 3]},${mesh.positions[v * 3 + 1]}`, [...mesh.colors!.subarray(v * 3, v * 3 + 3)]);
    const corners = (x0: number) => [[x0, 1], [x0, 0], [x0 + 1, 0], [x0 + 1, 1]].map(([x, y]) => byCorner.get(`${x},${y}`)!);
    expectClose(corners(0).flat(), float3);
    expectClose(corners(2).flat(), [[255, 128, 0], [0, 51, 255], [255, 255, 255], [1, 2, 3]].flat().map((c) => c / 255));
    expectClose(corners(4).flat(), [[65535, 32768, 0], [0, 13107, 65535], [65535, 65535, 65535], [1, 2, 3]].flat().map((c) => c / 65535));
    expect(corners(6).flat()).toEqual(Array(12).fill(1));
    expect(mesh.fileMaterials!.materials.every((m) => m.vertexColors)).toBe(true);
  });

  it('a file without COLOR_0 has no colors and no vertex-colored material', async () => {
    const { doc, quad } = model();
    quad({ material: doc.createMaterial('m') });
    const mesh = await decodeDoc(doc);
    expect(mesh.colors ?? null).toBeNull();
    expect(mesh.fileMaterials!.materials.some((m) => m.vertexColors)).toBe(false);
  });
});

describe('material extensions', () => {
  const withMaterial = async (make: (doc: Document, texture: (name: string) => GltfTexture) => GltfMaterial) => {
    const { doc, quad, texture } = model();
    quad({ material: make(doc, texture) });
    const mesh = await decodeDoc(doc);
    return { material: materialsOf(mesh)[0], warnings: mesh.warnings ?? [] };
  };

  it('KHR_materials_emissive_strength multiplies the emission: its intensity', async () => {
    const { material, warnings } = await withMaterial((doc) =>
      doc.createMaterial('e').setEmissiveFactor([1, 0.5, 0]).setExtension('KHR_materials_emissive_strength', doc.createExtension(KHRMaterialsEmissiveStrength).createEmissiveStrength().setEmissiveStrength(3)));
    expect(material.emission).toEqual({ color: [1, 0.5, 0], intensity: 3 });
    expect(warnings).toEqual([]);
    const black = await withMaterial((doc) => doc.createMaterial('b').setExtension('KHR_materials_emissive_strength', doc.createExtension(KHRMaterialsEmissiveStrength).createEmissiveStrength().setEmissiveStrength(5)));
    expect(black.material.emission).toBeUndefined();
  });

  it('KHR_materials_ior: kept in [1.01, 4]; below 1.01 (glTF allows 1 and 0) raised, with a warning naming the material', async () => {
    const ior = (value: number) => withMaterial((doc) => doc.createMaterial('glass').setExtension('KHR_materials_ior', doc.createExtension(KHRMaterialsIOR).createIOR().setIOR(value)));
    const kept = await ior(1.33);
    expect(kept.material.ior).toBeCloseTo(1.33, 6);
    expect(kept.warnings).toEqual([]);
    for (const low of [1, 0]) {
      const raised = await ior(low);
      expect(raised.material.ior).toBe(1.01);
      expect(raised.warnings).toEqual([expect.stringMatching(new RegExp(`materials\\[0\\] "glass": KHR_materials_ior ${low} becomes 1.01`))]);
    }
    const high = await ior(5);
    expect(high.material.ior).toBe(4);
    expect(high.warnings).toHaveLength(1);
    expect((await withMaterial((doc) => doc.createMaterial('plain'))).material.ior).toBe(principled({}).ior);
  });

  it('KHR_materials_transmission: factor x texture.r as specTrans', async () => {
    const transmission = (doc: Document) => doc.createExtension(KHRMaterialsTransmission).createTransmission().setTransmissionFactor(0.7);
    expect((await withMaterial((doc) => doc.createMaterial('t').setExtension('KHR_materials_transmission', transmission(doc)))).material.specTrans).toBeCloseTo(0.7, 6);
    const textured = await withMaterial((doc, texture) => doc.createMaterial('t').setExtension('KHR_materials_transmission', transmission(doc).setTransmissionTexture(texture('t'))));
    expect(textured.material.specTrans).toMatchObject({ image: '#0', channel: 'r' });
    expect((textured.material.specTrans as Texture).scale).toBeCloseTo(0.7, 6);
  });

  it('KHR_materials_clearcoat: factor (x texture.r) as clearcoat, clearcoatGloss = 1 - roughness; its roughness and normal textures ignored with a warning', async () => {
    const coat = (doc: Document) => doc.createExtension(KHRMaterialsClearcoat).createClearcoat().setClearcoatFactor(0.6).setClearcoatRoughnessFactor(0.3);
    const plain = await withMaterial((doc) => doc.createMaterial('c').setExtension('KHR_materials_clearcoat', coat(doc)));
    expect(plain.material.clearcoat).toBeCloseTo(0.6, 6);
    expect(plain.material.clearcoatGloss).toBeCloseTo(0.7, 6);
    expect(plain.warnings).toEqual([]);
    const textured = await withMaterial((doc, texture) => doc.createMaterial('c').setExtension('KHR_materials_clearcoat', coat(doc).setClearcoatTexture(texture('c')).setClearcoatRoughnessTexture(texture('r'))));
    expect(textured.material.clearcoat).toMatchObject({ image: '#0', channel: 'r' });
    expect((textured.material.clearcoat as Texture).scale).toBeCloseTo(0.6, 6);
    expect(textured.warnings).toEqual([expect.stringMatching(/materials\[0\] "c": the clear coat's roughness and normal textures are ignored/)]);
  });
});

describe('extensions the renderer ignores', () => {
  it('are listed, sorted, in one warning; the ones it reads are not', async () => {
    const { doc, quad, texture, transform } = model();
    const m = doc.createMaterial('m').setBaseColorTexture(texture('a'))
      .setExtension('KHR_materials_sheen', doc.createExtension(KHRMaterialsSheen).createSheen().setSheenColorFactor([1, 1, 1]))
      .setExtension('KHR_materials_ior', doc.createExtension(KHRMaterialsIOR).createIOR().setIOR(1.4));
    transform(m.getBaseColorTextureInfo(), { rotation: 0.2 });
    quad({ material: m });
    const mesh = await decodeJson(doc, (json) => json.extensionsUsed.push('EXT_foo'));
    const listed = mesh.warnings!.filter((w) => /extensions/.test(w));
    expect(listed).toEqual(['ignores the glTF extensions EXT_foo, KHR_materials_sheen']);
  });
});

describe('KHR_lights_punctual', () => {
  it('point, spot and directional lights placed by their nodes; cones in radians become degrees; range is ignored with a warning', async () => {
    const { doc, scene, quad } = model();
    quad();
    const lights = doc.createExtension(KHRLightsPunctual);
    scene.addChild(doc.createNode('point').setTranslation([1, 2, 3]).setExtension('KHR_lights_punctual', lights.createLight().setType('point').setIntensity(5).setColor([1, 0.5, 0.25])));
    // The spot turned 90 degrees about x: -z becomes -y (it shines down).
    const down: [number, number, number, number] = [-Math.SQRT1_2, 0, 0, Math.SQRT1_2];
    scene.addChild(doc.createNode('spot').setTranslation([0, 4, 0]).setRotation(down)
      .setExtension('KHR_lights_punctual', lights.createLight().setType('spot').setIntensity(20).setInnerConeAngle(0.2).setOuterConeAngle(0.6).setRange(10)));
    scene.addChild(doc.createNode('default spot').setExtension('KHR_lights_punctual', lights.createLight().setType('spot')));
    // A directional light under a parent turned 90 degrees about y: -z becomes -x.
    const parent = doc.createNode('parent').setRotation([0, Math.SQRT1_2, 0, Math.SQRT1_2]).setTranslation([9, 9, 9]);
    parent.addChild(doc.createNode('sun').setExtension('KHR_lights_punctual', lights.createLight().setType('directional').setIntensity(2)));
    scene.addChild(parent);
    const mesh = await decodeDoc(doc);
    const [point, spot, defaultSpot, sun] = mesh.lights! as Record<string, any>[];
    expect(point).toMatchObject({ type: 'point', intensity: 5, color: [1, 0.5, 0.25] });
    expectClose(point.position, [1, 2, 3]);
    expect(spot.type).toBe('spot');
    expectClose(spot.position, [0, 4, 0]);
    expectClose(sub(spot.target, spot.position), [0, -1, 0]);
    expect(spot.intensity).toBe(20);
    expect(spot.cutoffAngle).toBeCloseTo(0.6 * DEG, 6);
    expect(spot.beamWidth).toBeCloseTo(0.2 * DEG, 6);
    expect(defaultSpot.cutoffAngle).toBeCloseTo(45, 6);
    expect(defaultSpot.beamWidth).toBe(0);
    expect(sun).toMatchObject({ type: 'directional', irradiance: 2 });
    expectClose(sun.direction, [-1, 0, 0]);
    expect(mesh.warnings).toEqual([expect.stringMatching(/ignores the `range` of 1 KHR_lights_punctual light\b/)]);
    // In a scene, the mesh's transform places them.
    const placed = resolveFileMaterials(parseScene({ version: 3, camera, meshes: [{ file: 'm.glb', position: [10, 0, 0] }] }), { maps: new Map(), meshes: new Map([['m.glb', mesh]]), images: new Map() });
    expectClose((placed.scene.lights.find((l) => l.type === 'point') as Record<string, any>).position, [11, 2, 3]);
  });
});

describe('bad inputs: clear messages naming the file, the primitive or the reference', () => {
  const scene = (file: string) => parseScene({ version: 3, camera, meshes: [{ file }] });
  const issuesOf = async (file: string, files: Record<string, Uint8Array>) => {
    try {
      await loadSceneAssets(scene(file), async (name) => {
        if (!(name in files)) throw new Error(`ENOENT: no such file ${name}`);
        return files[name];
      });
    } catch (error) {
      if (error instanceof SceneError) return error.issues;
      throw error;
    }
    return [];
  };

  it('a .gltf whose .bin is missing: the issue at meshes[0].file names the .bin', async () => {
    const { doc, quad } = model();
    quad();
    doc.getRoot().listBuffers()[0].setURI('quad.bin');
    const { json } = await io().writeJSON(doc);
    const issues = await issuesOf('models/quad.gltf', { 'models/quad.gltf': new TextEncoder().encode(JSON.stringify(json)) });
    expect(issues).toEqual([{ path: 'meshes[0].file', message: expect.stringMatching(/^"models\/quad.gltf": its buffer "quad.bin" is missing \(ENOENT: no such file models\/quad.bin\)/) }]);
  });

  it('a .gltf whose image beside it is missing: the issue at meshes[0].file names the image and the file', async () => {
    const { doc, quad, texture } = model();
    quad({ material: doc.createMaterial('m').setBaseColorTexture(texture('wood').setURI('tex/wood.png')) });
    const { bytes } = await gltfJson(doc, () => {}, false);
    const issues = await issuesOf('models/m.gltf', { 'models/m.gltf': bytes });
    expect(issues).toEqual([{ path: 'meshes[0].file', message: expect.stringMatching(/^"models\/tex\/wood.png": "models\/tex\/wood.png", which "models\/m.gltf" names, is missing/) }]);
    // With the image there, it loads under its scene-relative name.
    const assets = await loadSceneAssets(scene('models/m.gltf'), async (name) => ({ 'models/m.gltf': bytes, 'models/tex/wood.png': PNG })[name]!);
    expect([...assets.images!.keys()]).toEqual(['models/tex/wood.png']);
  });

  it('a .glb that names an image outside itself: an error naming the image', async () => {
    const { doc, quad, texture } = model();
    quad({ material: doc.createMaterial('m').setBaseColorTexture(texture('t')) });
    const glbBytes = await glb(doc);
    const view = new DataView(glbBytes.buffer, glbBytes.byteOffset);
    const jsonLength = view.getUint32(12, true);
    const json = JSON.parse(new TextDecoder().decode(glbBytes.subarray(20, 20 + jsonLength)));
    json.images[0] = { uri: 'tex.png', mimeType: 'image/png' };
    const text = new TextEncoder().encode(JSON.stringify(json).padEnd(Math.ceil(JSON.stringify(json).length / 4) * 4, ' '));
    const rest = glbBytes.subarray(20 + jsonLength);
    const out = new Uint8Array(20 + text.length + rest.length);
    const header = new DataView(out.buffer);
    [0x46546c67, 2, out.length, text.length, 0x4e4f534a].forEach((word, i) => header.setUint32(i * 4, word, true));
    out.set(text, 20);
    out.set(rest, 20 + text.length);
    await expect(decodeMesh(out, 'a.glb')).rejects.toThrow(/the .glb names "tex.png" outside itself/);
  });

  it('indices out of range: the message names meshes[m].primitives[p]', async () => {
    const { doc, quad } = model();
    quad();
    quad({ x0: 2, indices: [0, 1, 2, 0, 2, 9] });
    await expect(decodeDoc(doc)).rejects.toThrow(/meshes\[1\]\.primitives\[0\]: an index references vertex 9, but the primitive has 4 vertices/);
  });

  it('a texture index that does not exist names the material slot and the count', async () => {
    const { doc, quad, texture } = model();
    quad({ material: doc.createMaterial('m').setBaseColorTexture(texture('a')) });
    await expect(decodeJson(doc, (json) => (json.materials[0].normalTexture = { index: 7 }))).rejects.toThrow(/materials\[0\]\.normalTexture: texture 7 does not exist \(the file has 1\)/);
    await expect(decodeJson(doc, (json) => (json.materials[0].pbrMetallicRoughness.baseColorTexture.index = -1))).rejects.toThrow(/materials\[0\]\.pbrMetallicRoughness\.baseColorTexture: texture -1 does not exist/);
    await expect(decodeJson(doc, (json) => (json.textures[0].source = 3))).rejects.toThrow(/textures\[0\]: image 3 does not exist \(the file has 1\)/);
  });

  it('a KTX2/Basis image is an error that names it (KHR_texture_basisu, or a KTX2 image without it)', async () => {
    const { doc, quad } = model();
    doc.createExtension(KHRTextureBasisu).setRequired(true);
    const ktx = doc.createTexture('k').setImage(new Uint8Array([0xab, 0x4b, 0x54, 0x58, 0x20, 0x32, 0x30, 0xbb])).setMimeType('image/ktx2');
    quad({ material: doc.createMaterial('m').setBaseColorTexture(ktx) });
    await expect(decodeDoc(doc)).rejects.toThrow(/KTX2\/Basis \(KHR_texture_basisu\)/);
    await expect(decodeJson(doc, (json) => {
      delete json.extensionsUsed;
      delete json.extensionsRequired;
      json.textures[0] = { source: 0 };
    })).rejects.toThrow(/images\[0\] is KTX2\/Basis/);
  });

  describe('a 2 GB .glb is refused before it is read whole', () => {
    const dir = mkdtempSync(join(tmpdir(), 'gltf-big-'));
    afterAll(() => rmSync(dir, { recursive: true, force: true }));

    it('a GLB header declaring more than MAX_MESH_FILE_BYTES (1 GiB)', async () => {
      const header = new Uint8Array(28);
      const view = new DataView(header.buffer);
      view.setUint32(0, 0x46546c67, true); // "glTF"
      view.setUint32(4, 2, true);
      view.setUint32(8, 2 ** 31, true);
      view.setUint32(12, 4, true);
      view.setUint32(16, 0x4e4f534a, true); // "JSON"
      header.set(new TextEncoder().encode('{}  '), 20);
      await expect(decodeMesh(header, 'big.glb')).rejects.toThrow(/the GLB header declares 2147483648 bytes; files above 1 GiB \(MAX_MESH_FILE_BYTES\) are not read/);
      // At the limit, the header passes and the (empty) JSON is what fails.
      view.setUint32(8, 2 ** 30, true);
      await expect(decodeMesh(header, 'big.glb')).rejects.toThrow(/not a valid glTF file/);
    });

    it('a sparse 2 GB file, by its size, through readMeshFile and the CLI\'s readSceneFiles', async () => {
      const big = join(dir, 'big.glb');
      writeFileSync(big, '');
      truncateSync(big, 2e9); // sparse: no 2 GB are written
      await expect(readMeshFile(big)).rejects.toThrow(/the file is 2000000000 bytes; files above 1 GiB \(MAX_MESH_FILE_BYTES\) are not read/);
      // A .gltf's .bin beside it, by its size too.
      const { doc, quad } = model();
      quad();
      doc.getRoot().listBuffers()[0].setURI('big.bin');
      writeFileSync(join(dir, 'big.gltf'), JSON.stringify((await io().writeJSON(doc)).json));
      writeFileSync(join(dir, 'big.bin'), '');
      truncateSync(join(dir, 'big.bin'), 2e9);
      await expect(readMeshFile(join(dir, 'big.gltf'))).rejects.toThrow(/its buffer "big.bin": the file is 2000000000 bytes; files above 1 GiB/);
      const sceneFile = join(dir, 'scene.json');
      const error = await readSceneFiles(scene('big.glb'), sceneFile).catch((e: unknown) => e);
      expect(error).toBeInstanceOf(SceneError);
      expect((error as SceneError).issues).toEqual([{ path: 'meshes[0].file', message: '"big.glb": the file is 2000000000 bytes; files above 1 GiB (MAX_MESH_FILE_BYTES) are not read' }]);
    });
  });

  it('a Draco primitive when the decoder cannot run: an error saying so, with the reason; it is retried on the next file', async () => {
    const bytes = new Uint8Array(readFileSync(new URL('meshes/ico-flat-draco.glb', FIXTURES)));
    for (let attempt = 0; attempt < 2; attempt++) {
      await expect(decodeMesh(bytes, 'ico.glb')).rejects.toThrow(/the file is Draco-compressed and the Draco decoder \(WebAssembly\) cannot run here \(.*wasm-unsafe-eval.*\): convert it .*gltf-transform\/cli copy/);
    }
  });
});

describe('panels.glb end to end: loadSceneAssets + resolveFileMaterials', () => {
  it('5 materials resolve into 5 meshes with their materials; its 5 embedded images are loaded under ../meshes/panels.glb#N', async () => {
    const scenes = new URL('scenes/', FIXTURES);
    const scene = parseScene(JSON.parse(readFileSync(new URL('gltf-materials.json', scenes), 'utf8')));
    const assets = await loadSceneAssets(scene, async (name) => new Uint8Array(readFileSync(new URL(name, scenes))));
    const file = '../meshes/panels.glb';
    expect([...assets.images!.keys()].sort()).toEqual([0, 1, 2, 3, 4].map((n) => `${file}#${n}`));
    for (const image of assets.images!.values()) expect(image.width * image.height).toBeGreaterThan(0);
    const { scene: resolved, assets: resolvedAssets } = resolveFileMaterials(scene, assets);
    expect(resolved.meshes.map((m) => m.file)).toEqual([0, 1, 2, 3, 4].map((k) => `${file}#material${k}`));
    for (const m of resolved.meshes) expect(resolvedAssets.meshes.get(m.file)!.indices.length).toBeGreaterThan(0);
    const [rotated, emissive, cutout, normalMapped, coated] = resolved.meshes.map((m) => m.material as PrincipledMaterial);

    const base = rotated.baseColor as Texture;
    expect(base.image).toBe(`${file}#1`);
    expect(base.uv.offset).toEqual([0.1, 0]);
    expect(base.uv.scale).toEqual([2, 2]);
    expect(base.uv.rotation).toBeCloseTo(17.19, 2); // 0.3 rad
    expect(rotated.metallic).toMatchObject({ image: `${file}#0`, channel: 'b', scale: 1 });
    expect(rotated.roughness).toMatchObject({ image: `${file}#0`, channel: 'g' });
    expect((rotated.roughness as Texture).scale).toBeCloseTo(0.9, 6);

    expect(emissive.emission).toMatchObject({ color: [1, 1, 1], intensity: 3, texture: { image: `${file}#2` } });
    expectClose(emissive.baseColor as number[], [0.1, 0.1, 0.1]);

    expect(cutout.opacity).toMatchObject({ image: `${file}#4`, channel: 'a', cutoff: 0.5, scale: 1 });
    expect(cutout.baseColor).toMatchObject({ image: `${file}#4` });

    expect(normalMapped.normalMap).toMatchObject({ image: `${file}#3`, scale: 1 });
    expect([normalMapped.metallic, normalMapped.roughness]).toEqual([1, 0.25]);

    expect(coated.clearcoat).toBe(1);
    expect(coated.clearcoatGloss).toBeCloseTo(0.9, 6);
    expectClose(coated.baseColor as number[], [0.9, 0.2, 0.15]);
    expect(coated.emission).toBeUndefined();
    expect(coated.opacity).toBe(1);
  });
});

describe('a version-3 mesh without material on a file that has no materials', () => {
  it('resolves to the default material (the renderer never sees a null material)', async () => {
    const { resolveFileMaterials } = await import('../../src/scene/fileMaterials');
    const { parseScene } = await import('../../src/scene/schema');
    const { defaultMaterial } = await import('../../src/materials/registry');
    const scene = parseScene({ version: 3, camera: { position: [0, 1, 5], target: [0, 0, 0] }, meshes: [{ file: 'plain.ply' }] });
    expect(scene.meshes[0].material).toBeNull();
    const mesh = { positions: new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]), normals: null, indices: new Uint32Array([0, 1, 2]) };
    const resolved = resolveFileMaterials(scene, { maps: new Map(), meshes: new Map([['plain.ply', mesh]]), images: new Map() });
    expect(resolved.scene.meshes.map((m) => m.material)).toEqual([defaultMaterial()]);
  });
});
