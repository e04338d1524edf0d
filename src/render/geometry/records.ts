/**
 * Records derived from the prepared geometry (pure: no GL), uploaded by
 * src/render/passes/assetTextures.ts: the instance table and the
 * emissive-triangle table.
 */
import { inverseAffine } from '../../scene/mesh';
import { buildAliasTable } from '../aliasTable';
import { BVH_TEXTURE_WIDTH } from '../bvh';
import { INSTANCE } from '../layout/scene';
import { packRecord } from '../layout/records';
import type { MeshEmitterSlots } from '../packScene';
import { triangleArea, type WorldMeshes } from './world';
import { srgbToLinear } from '../../scene/color';
import { bitmapLookup, transformUv } from '../../scene/texture/bitmapLookup';
import type { TextureImage } from '../../scene/texture/image';
import type { Texture } from '../../scene/texture/texture';
import type { TriangleMesh } from '../../scene/types';

/**
 * The instance table (InstanceRecord, layout/scene.ts): the world group
 * first when it is stored (identity, its triangles' own meshes), then
 * every mesh of each shared group with its matrices and mesh index.
 */
export function instanceRecords(world: WorldMeshes, roots: readonly number[]): Float32Array {
  const { groups } = world;
  const identity = new Float64Array([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]);
  const entries: { toWorld: Float64Array; root: number; mesh: number }[] = [];
  if (groups.world.length > 0) entries.push({ toWorld: identity, root: roots[0], mesh: -1 });
  const firstShared = groups.world.length > 0 ? 1 : 0;
  groups.shared.forEach((users, g) => {
    for (const i of users) entries.push({ toWorld: world.toWorld[i], root: roots[firstShared + g], mesh: i });
  });
  const out = new Float32Array(entries.length * INSTANCE.texels * 4);
  entries.forEach((e, k) => out.set(packRecord(INSTANCE, { ...matrixRows(e.toWorld), root: e.root, mesh: e.mesh }), k * INSTANCE.texels * 4));
  return out;
}

/** The rows (3x4) of an affine column-major matrix and of its inverse, as InstanceRecord fields. */
function matrixRows(m: Float64Array): Record<string, number[]> {
  const row = (a: ArrayLike<number>, r: number) => [a[r], a[4 + r], a[8 + r], a[12 + r]];
  const inv = inverseAffine(m);
  return {
    toObjectX: row(inv, 0), toObjectY: row(inv, 1), toObjectZ: row(inv, 2),
    toWorldX: row(m, 0), toWorldY: row(m, 1), toWorldZ: row(m, 2),
  };
}

/**
 * The mean luminance of a textured emission over each triangle's footprint
 * in its image (the format's "power from its texture"): the filtered
 * texture (bitmapLookup: Mitsuba's filtering, sRGB decoded) at stratified
 * points of the triangle, as many as its footprint has texels (4 to 64).
 * 16-bit and float images are read at the nearest texel.
 */
export function emissionMeans(mesh: TriangleMesh, texture: Texture, image: TextureImage): Float32Array {
  const triangles = mesh.indices.length / 3;
  const out = new Float32Array(triangles);
  const uvs = mesh.uvs;
  if (!uvs) return out.fill(1);
  const corner = (t: number, c: number): [number, number] => [uvs[mesh.indices[3 * t + c] * 2], uvs[mesh.indices[3 * t + c] * 2 + 1]];
  const value = texelReader(texture, image);
  for (let t = 0; t < triangles; t++) {
    const [a, b, c] = [corner(t, 0), corner(t, 1), corner(t, 2)];
    const footprint = Math.abs((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])) * 0.5 * image.width * image.height;
    const side = Math.max(2, Math.min(8, Math.ceil(Math.sqrt(footprint))));
    let sum = 0;
    for (let i = 0; i < side; i++)
      for (let j = 0; j < side; j++) {
        // A stratified point of the unit square folded onto the triangle.
        let [x, y] = [(i + 0.5) / side, (j + 0.5) / side];
        if (x + y > 1) [x, y] = [1 - x, 1 - y];
        const uv: [number, number] = [a[0] + x * (b[0] - a[0]) + y * (c[0] - a[0]), a[1] + x * (b[1] - a[1]) + y * (c[1] - a[1])];
        sum += value(uv);
      }
    out[t] = sum / (side * side);
  }
  return out;
}

/** The luminance of the texture's RGB at uv (its scale excluded: the record holds it). */
function texelReader(texture: Texture, image: TextureImage): (uv: [number, number]) => number {
  const lum = (r: number, g: number, b: number) => 0.2126 * r + 0.7152 * g + 0.0722 * b;
  if (image.data instanceof Uint8Array) {
    const rgba = { width: image.width, height: image.height, data: image.data };
    return (uv) => lum(...(bitmapLookup(rgba, uv, { srgb: true, transform: texture.uv }).slice(0, 3) as [number, number, number]));
  }
  const data = image.data;
  const max = data instanceof Uint16Array ? 65535 : 1;
  const decode = data instanceof Uint16Array ? srgbToLinear : (x: number) => x;
  return (uv) => {
    const [u, v] = transformUv(uv, texture.uv);
    const x = ((Math.floor(u * image.width) % image.width) + image.width) % image.width;
    const y = ((Math.floor(v * image.height) % image.height) + image.height) % image.height;
    const o = (y * image.width + x) * 4;
    return Number.isFinite(u + v) ? lum(decode(data[o] / max), decode(data[o + 1] / max), decode(data[o + 2] / max)) : 0;
  };
}

/** The area-weighted mean of per-triangle values over a mesh (its textured emission's mean luminance). */
export function areaMean(mesh: TriangleMesh, values: Float32Array): number {
  let [sum, area] = [0, 0];
  for (let t = 0; t < values.length; t++) {
    const a = triangleArea(mesh.positions, mesh.indices, t);
    sum += a * values[t];
    area += a;
  }
  return area > 0 ? sum / area : 0;
}

/**
 * The textured emissions' per-triangle means of the scene's meshes (by
 * mesh index), for light sampling; cached per mesh data, texture and image.
 */
export function textureEmissionMeans(
  scene: { meshes: readonly { material: { emission?: { texture?: Texture } } }[] },
  world: WorldMeshes,
  images: ReadonlyMap<string, TextureImage>,
  cache: WeakMap<object, Map<string, Float32Array>>,
): Map<number, Float32Array> {
  const out = new Map<number, Float32Array>();
  scene.meshes.forEach((mesh, i) => {
    const texture = mesh.material.emission?.texture;
    const data = world.meshes[i];
    const image = texture && images.get(texture.image);
    if (!texture || !data || !image) return;
    let byTexture = cache.get(data);
    if (!byTexture) cache.set(data, (byTexture = new Map()));
    const key = JSON.stringify(texture);
    let means = byTexture.get(key);
    if (!means) byTexture.set(key, (means = emissionMeans(data, texture, image)));
    out.set(i, means);
  });
  return out;
}

/** Each triangle's weight for light sampling: its area times its mean emission (floored, so none is never sampled). */
function triangleWeights(areas: number[], means: Float32Array | undefined): number[] {
  if (!means) return areas;
  const area = areas.reduce((a, b) => a + b, 0);
  const mean = areas.reduce((s, a, t) => s + a * means[t], 0) / (area || 1);
  return areas.map((a, t) => a * Math.max(means[t], 1e-3 * mean));
}

/**
 * The emissive triangles for lights/mesh_emitter.glsl, BVH_TEXTURE_WIDTH
 * texels a row: slot `first + k` of a mesh's range holds (BVH index of its
 * triangle k, alias threshold, its alias slot k', (triangle k's share of
 * the mesh's weight) / (its share of the area)) of a per-mesh alias table
 * that picks triangles in proportion to their area, or for a textured
 * emission (`means`, per mesh) to their power.
 */
export function emissiveTriangleRecords(
  world: WorldMeshes,
  triangleOrder: Uint32Array,
  emitters: readonly MeshEmitterSlots[],
  means: ReadonlyMap<number, Float32Array> = new Map(),
): Float32Array {
    const bvhIndex = new Uint32Array(triangleOrder.length);
    triangleOrder.forEach((input, j) => (bvhIndex[input] = j));
    // Emissive meshes are in the world group, the first: its inputs are its meshes' triangles in order.
    const firstInput: number[] = [];
    world.groups.world.reduce((sum, i) => ((firstInput[i] = sum), sum + world.sizes[i].triangles), 0);
    const slots = emitters.reduce((n, e) => Math.max(n, e.first + e.count), 0);
    const width = BVH_TEXTURE_WIDTH;
    const data = new Float32Array(width * Math.max(1, Math.ceil(slots / width)) * 4);
    for (const e of emitters) {
      const mesh = world.meshes[e.mesh]!;
      const areas = Array.from({ length: e.count }, (_, t) => triangleArea(mesh.positions, mesh.indices, t));
      const weights = triangleWeights(areas, means.get(e.mesh));
      const table = buildAliasTable(weights);
      const [area, weight] = [areas, weights].map((v) => v.reduce((a, b) => a + b, 0));
      for (let k = 0; k < e.count; k++) {
        const o = (e.first + k) * 4;
        data[o] = bvhIndex[firstInput[e.mesh] + k];
        data[o + 1] = table.threshold[k];
        data[o + 2] = table.alias[k];
        data[o + 3] = areas[k] > 0 ? weights[k] / weight / (areas[k] / area) : 1;
      }
    }
  return data;
}
