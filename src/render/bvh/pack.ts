/**
 * Packs a BVH and its triangles into RGBA32F texture data for the GLSL
 * traversal (src/shaders/scene/bvh.glsl). Integers (child and triangle
 * indices, counts, material and mesh indices) are stored as float values:
 * exact below 2^24, which the texture size caps anyway, and no denormal bit
 * patterns for a GPU to flush.
 *
 * Both are 2D array textures BVH_TEXTURE_WIDTH (2048) texels wide and
 * BVH_LAYER_ROWS (512) high, as many layers as needed (a single layer only
 * as high as needed): texel i is at (i % 2048, (i / 2048) % 512, layer
 * i / 2^20), masks and shifts in the shader. WebGL2 guarantees
 * MAX_TEXTURE_SIZE >= 2048 and MAX_ARRAY_TEXTURE_LAYERS >= 256, so the layout
 * works on every WebGL2 device; short layers waste at most 16 MB of padding.
 *
 * uBvhNodes: 2 texels per node, node i at texels 2i and 2i + 1:
 *   (min.xyz, a), (max.xyz, b)
 *   interior: b = 0, a = index of the second child (the first is i + 1)
 *   leaf:     b = triangle count (>= 1), a = first triangle
 * uBvhTriangles: triangle j (in BVH order) at texels 3j .. 3j + 2:
 *   (v0.xyz, material index), (v1.xyz, normals texel or -1 when flat),
 *   (v2.xyz, mesh index); a smooth triangle's vertex normals n0, n1, n2
 *   (unit, w = 0) follow all triangles, at its normals texel .. + 2.
 *
 * Limit: texel indices are stored as floats, exact up to 2^24 = 16.7M
 * texels (16 layers): 2.79M smooth or 5.59M flat triangles in total (6 or 3
 * texels each). Memory is 96 bytes per smooth triangle (48 flat) plus about
 * 32 bytes per triangle for the nodes: ~125 MB for 1M smooth triangles.
 */
import type { Bvh, BvhMeshInput } from './build';

export const BVH_TEXTURE_WIDTH = 2048;
export const BVH_LAYER_ROWS = 512;
export const BVH_NODE_TEXELS = 2;
export const BVH_TRIANGLE_TEXELS = 3;
/** Texel indices are floats in the textures: exact below 2^24. */
export const BVH_MAX_TEXELS = 2 ** 24;
/** The documented total (every triangle smooth: 6 texels each). */
export const MAX_TRIANGLES = Math.floor(BVH_MAX_TEXELS / 6);

/** A 2D RGBA32F texture's data: width * height * 4 floats. */
export interface TextureData {
  data: Float32Array;
  width: number;
  height: number;
}

/** A 2D array texture's data (the BVH's): width * height * layers * 4 floats (padded). */
export interface LayeredTextureData extends TextureData {
  layers: number;
}

export interface PackedBvh {
  nodes: LayeredTextureData;
  triangles: LayeredTextureData;
  nodeCount: number;
  triangleCount: number;
  /** BVH triangle j -> input triangle id (meshes concatenated in input order). */
  triangleOrder: Uint32Array;
  depth: number;
}

/** Storage for `texels` texels in the layout above. */
export function bvhTexture(texels: number): LayeredTextureData {
  const width = BVH_TEXTURE_WIDTH;
  const layers = Math.max(1, Math.ceil(texels / (width * BVH_LAYER_ROWS)));
  const height = layers > 1 ? BVH_LAYER_ROWS : Math.max(1, Math.ceil(texels / width));
  return { data: new Float32Array(width * height * layers * 4), width, height, layers };
}

export function packBvh(bvh: Bvh, meshes: BvhMeshInput[]): PackedBvh {
  const n = bvh.triangleOrder.length;
  const meshOf = new Uint32Array(meshes.length + 1); // first input triangle of each mesh
  meshes.forEach((m, i) => (meshOf[i + 1] = meshOf[i] + m.indices.length / 3));
  const smoothCount = meshes.reduce((sum, m) => sum + (m.normals ? m.indices.length / 3 : 0), 0);
  const triangleTexels = n * BVH_TRIANGLE_TEXELS + smoothCount * 3;
  if (triangleTexels > BVH_MAX_TEXELS) {
    throw new Error(`${n} triangles exceed the BVH texture limit (${MAX_TRIANGLES} smooth triangles in total)`);
  }
  const nodes = bvhTexture(bvh.nodeCount * BVH_NODE_TEXELS);
  for (let i = 0; i < bvh.nodeCount; i++) {
    const o = i * 8;
    for (let k = 0; k < 3; k++) {
      nodes.data[o + k] = bvh.nodeBounds[i * 6 + k];
      nodes.data[o + 4 + k] = bvh.nodeBounds[i * 6 + 3 + k];
    }
    nodes.data[o + 3] = bvh.nodeData[i * 2];
    nodes.data[o + 7] = bvh.nodeData[i * 2 + 1];
  }
  const triangles = bvhTexture(triangleTexels);
  const out = triangles.data;
  let normalTexel = n * BVH_TRIANGLE_TEXELS;
  let mesh = 0;
  for (let j = 0; j < n; j++) {
    const id = bvh.triangleOrder[j];
    mesh = findMesh(meshOf, id, mesh);
    const { positions, normals, indices, material } = meshes[mesh];
    const local = (id - meshOf[mesh]) * 3;
    const o = j * BVH_TRIANGLE_TEXELS * 4;
    for (let c = 0; c < 3; c++) {
      const v = indices[local + c];
      for (let k = 0; k < 3; k++) out[o + c * 4 + k] = positions[v * 3 + k];
      if (normals) for (let k = 0; k < 3; k++) out[normalTexel * 4 + c * 4 + k] = normals[v * 3 + k];
    }
    out[o + 3] = material;
    out[o + 7] = normals ? normalTexel : -1;
    out[o + 11] = mesh;
    if (normals) normalTexel += 3;
  }
  return { nodes, triangles, nodeCount: bvh.nodeCount, triangleCount: n, triangleOrder: bvh.triangleOrder, depth: bvh.depth };
}

/** The mesh holding input triangle `id`; starts from the last answer (ids often come in runs). */
function findMesh(meshOf: Uint32Array, id: number, guess: number): number {
  if (id >= meshOf[guess] && id < meshOf[guess + 1]) return guess;
  let lo = 0;
  let hi = meshOf.length - 2;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (meshOf[mid] <= id) lo = mid;
    else hi = mid - 1;
  }
  return lo;
}

/** The box around everything: the root node's (min xyz, max xyz). */
export function bvhBounds(packed: PackedBvh): [number[], number[]] {
  const d = packed.nodes.data;
  return [[d[0], d[1], d[2]], [d[4], d[5], d[6]]];
}
