/**
 * Packs a BVH and its triangles into one RGBA32F texture for the GLSL
 * traversal (src/shaders/scene/bvh.glsl). Integers (texel indices, mesh and
 * material indices) are stored as float values: exact below 2^24, and no
 * denormal bit patterns for a GPU to flush. The one exception, the nodes'
 * child codes, are bit patterns of normal floats (1 .. 2^32: see below).
 *
 * One texture, so that one traversal step fetches the same 7 texels whether
 * it visits a node or tests triangles (SwiftShader runs every fetch of a
 * loop body for all 4 lanes of a quad, whatever each lane does, and the
 * fetches are about a third of a step's cost: bench/bvh-kernel-ab.ts).
 *
 * A 2D array texture BVH_TEXTURE_WIDTH (2048) texels wide and
 * BVH_LAYER_ROWS (512) high, as many layers as needed (a single layer only
 * as high as needed): texel i is at (i % 2048, (i / 2048) % 512, layer
 * i / 2^20), masks and shifts in the shader. WebGL2 guarantees
 * MAX_TEXTURE_SIZE >= 2048 and MAX_ARRAY_TEXTURE_LAYERS >= 256, so the layout
 * works on every WebGL2 device; short layers waste at most 16 MB of padding.
 *
 * A step reads its 7 texels with one texel coordinate and constant offsets
 * (texelFetchOffset: cheaper on SwiftShader than 7 addresses), so no node
 * or triangle pair straddles a row: rows hold 681 triangles (2043 texels,
 * the last 5 zero) or 292 nodes (2044 texels).
 * Texels, in order:
 *   0 .. 6                 the root node (BVH_ROOT_NODE = 0)
 *   rows 0 ..              triangle j (BVH order) at texel triangleTexel(j): slot
 *                          s = j + 3 (the root takes row 0's first 3 slots) at
 *                          (s / 681) * 2048 + (s % 681) * 3 .. + 2: (v0.xyz, local material),
 *                          (v1.xyz, attributes), (v2.xyz, mesh index)
 *                          mesh index: the scene mesh (-1 in a shared group: its
 *                          instance gives the mesh); local material: the index
 *                          among the mesh's own materials (0: a mesh has one for
 *                          now). The material-table index is the mesh record's
 *                          materialBase + local (layout/scene.ts MESH), looked up
 *                          once per closest hit, so the texels hold no global
 *                          material slot: they depend only on the meshes'
 *                          geometry, transforms and order, never on the
 *                          spheres, lights, ground or materials.
 *                          attributes: where the triangle's per-corner attributes are
 *                          (read once per closest hit, never in the traversal loop):
 *                            -1          none (flat, no texture coordinates, no colors);
 *                            a >= 0      smooth: normals at a .. a + 2, and when n0.w is 1
 *                                        texture coordinates at a + 3, a + 4; when n1.w is 1
 *                                        vertex colors after them (a + 3 or a + 5 ..);
 *                            -2 - a      flat with texture coordinates at a, a + 1, and
 *                                        when the second uv texel's z is 1 vertex colors
 *                                        at a + 2 .. a + 4 (a flat triangle with colors and
 *                                        no uvs stores zero uvs: the same as none).
 *   from the next row      the attribute blocks, one per triangle that has any, in
 *                          triangle order: a smooth triangle's vertex normals n0, n1, n2
 *                          (unit; w = 0, n0.w = 1 when uvs follow, n1.w = 1 when colors
 *                          follow), then a textured triangle's corners' (u, v):
 *                          (u0, v0, u1, v1), (u2, v2, colors follow ? 1 : 0, 0), then the
 *                          corners' vertex colors (linear rgb; only for meshes whose
 *                          material multiplies its base color by them, glTF COLOR_0):
 *                          (c0.rgb, 0), (c1.rgb, 0), (c2.rgb, 0)
 *   from the next row      the other nodes, 292 to a row (7 texels each).
 *
 * The BVH is 4-wide (wide.ts collapses the binary SAH build): a node holds
 * its up to 4 children's boxes, so visiting it tests all of them, and a leaf
 * is known from its parent. A node at texel q, children c = 0 .. 3 in the
 * components (structure of arrays):
 *   q + 0, q + 1:  the children's min x, max x
 *   q + 2, q + 3:  min y, max y
 *   q + 4, q + 5:  min z, max z
 *   q + 6:         codes: the float whose bits are BVH_CODE_BIAS + ref * 16 + count
 *                  (nodeChildren decodes them): a leaf of `count` (1 .. 8)
 *                  triangles from texel `ref`, or (count 0) the child node at
 *                  texel `ref`; 0.0 for an empty slot.
 * A root that is a leaf (a few triangles) becomes a node with that one child.
 *
 * Limit: texel indices are stored as floats, exact up to 2^24 = 16.7M
 * texels (16 layers): triangles and attributes must end below that, which
 * MAX_TRIANGLES (2.09M, every triangle smooth and textured) ensures for
 * meshes without vertex colors; vertex colors take 3 texels more per
 * triangle, so with them the packer's bound is MAX_COLORED_TRIANGLES
 * (1.52M, every triangle smooth, textured and colored) and a scene past it
 * is refused here with a message naming both. Nodes are referred to by
 * their first texel. Memory per triangle: 48 bytes flat, 96 smooth, 32 more
 * with texture coordinates (80 flat, 128 smooth), 48 more with vertex
 * colors (80 more for a flat one without uvs: its zero uvs), plus 112 bytes
 * per wide node (about one per 3.6 triangles at the build's leaf sizes): ~130 MB for 1M smooth triangles, ~160 MB textured, ~208 MB
 * textured and colored.
 */
import type { Bvh, BvhMeshInput } from './build';
import { BVH_WIDTH, collapseBvh } from './wide';

export const BVH_TEXTURE_WIDTH = 2048;
export const BVH_LAYER_ROWS = 512;
/** A wide node's texels: 6 of its children's boxes (SoA), 1 of their codes (nodeChildren). */
export const BVH_NODE_TEXELS = 7;
/** Nodes per texture row (none straddles a row: 2044 texels, 4 spare). */
export const BVH_ROW_NODES = Math.floor(BVH_TEXTURE_WIDTH / BVH_NODE_TEXELS);
/** A child's code holds the float whose bits are BVH_CODE_BIAS + (ref * 16 + count): a normal float (1 .. 2^32, never a denormal a GPU could flush, nor a NaN); 0.0 an empty slot. */
export const BVH_CODE_BIAS = 0x3f800000;
export const BVH_TRIANGLE_TEXELS = 3;
/** Triangles per texture row (2043 texels): a 7-texel read from the row's last triangle (column 2040) stays in the row. */
export const BVH_ROW_TRIANGLES = Math.floor(BVH_TEXTURE_WIDTH / BVH_TRIANGLE_TEXELS) - 1;
/** The root node's first texel: texels 0 .. 6 of row 0. Nodes are referred to by their first texel. */
export const BVH_ROOT_NODE = 0;
/** Triangle slots of row 0 the root takes (texels 0 .. 8): triangle j is in slot j + this. */
export const BVH_FIRST_SLOT = Math.ceil(BVH_NODE_TEXELS / BVH_TRIANGLE_TEXELS);
/** Texel indices are floats in the textures: exact below 2^24. */
export const BVH_MAX_TEXELS = 2 ** 24;

/** First texel of triangle j. */
export const triangleTexel = (j: number): number => {
  const slot = j + BVH_FIRST_SLOT;
  return Math.floor(slot / BVH_ROW_TRIANGLES) * BVH_TEXTURE_WIDTH + (slot % BVH_ROW_TRIANGLES) * BVH_TRIANGLE_TEXELS;
};
/** The triangle whose first texel is `texel`. */
export const triangleAt = (texel: number): number => Math.floor(texel / BVH_TEXTURE_WIDTH) * BVH_ROW_TRIANGLES + Math.floor((texel % BVH_TEXTURE_WIDTH) / BVH_TRIANGLE_TEXELS) - BVH_FIRST_SLOT;
/** Where the attribute blocks start: the row after the triangles'. */
const attributesStart = (triangles: number) => Math.ceil((triangles + BVH_FIRST_SLOT) / BVH_ROW_TRIANGLES) * BVH_TEXTURE_WIDTH;

/** Texels of a triangle's attribute block: 3 of normals when smooth, 2 of texture coordinates when textured (or flat and colored), 3 of vertex colors when colored. */
export const NORMAL_TEXELS = 3;
export const UV_TEXELS = 2;
export const COLOR_TEXELS = 3;

/** The most triangles whose texels end below BVH_MAX_TEXELS when every one has `attributeTexels` of attributes. */
function mostTriangles(attributeTexels: number): number {
  let [lo, hi] = [0, Math.floor(BVH_MAX_TEXELS / (BVH_TRIANGLE_TEXELS + attributeTexels))];
  while (lo < hi) {
    const mid = Math.ceil((lo + hi) / 2);
    if (attributesStart(mid) + attributeTexels * mid <= BVH_MAX_TEXELS) lo = mid;
    else hi = mid - 1;
  }
  return lo;
}

/** The documented total: the most triangles when every one is smooth and textured (3 texels, 3 of normals, 2 of uvs). */
export const MAX_TRIANGLES = mostTriangles(NORMAL_TEXELS + UV_TEXELS);
/** The same with vertex colors on every triangle (3 texels more each). */
export const MAX_COLORED_TRIANGLES = mostTriangles(NORMAL_TEXELS + UV_TEXELS + COLOR_TEXELS);

/** The attribute texels of each triangle of `m` (the block layout above). */
function blockTexels(m: BvhMeshInput): number {
  const colors = !!m.colors;
  return (m.normals ? NORMAL_TEXELS : 0) + (m.uvs || (colors && !m.normals) ? UV_TEXELS : 0) + (colors ? COLOR_TEXELS : 0);
}

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
  /** Nodes, triangles and their attributes in the layout above. */
  texture: LayeredTextureData;
  /** Stored (interior) nodes, the root included. */
  nodeCount: number;
  triangleCount: number;
  /** BVH triangle j -> input triangle id (the groups' meshes concatenated in input order). */
  triangleOrder: Uint32Array;
  /** The deepest leaf's depth in the binary build (root = 0). */
  depth: number;
  /** The most entries the traversal's stack can hold (wide.ts stackEntries): at most MAX_WIDE_STACK. */
  stackEntries: number;
  /** Each group's root node (packBvhGroups); the first is BVH_ROOT_NODE. */
  roots: number[];
}

/** Storage for `texels` texels in the layout above. */
export function bvhTexture(texels: number): LayeredTextureData {
  const width = BVH_TEXTURE_WIDTH;
  const layers = Math.max(1, Math.ceil(texels / (width * BVH_LAYER_ROWS)));
  const height = layers > 1 ? BVH_LAYER_ROWS : Math.max(1, Math.ceil(texels / width));
  return { data: new Float32Array(width * height * layers * 4), width, height, layers };
}

export function packBvh(bvh: Bvh, meshes: BvhMeshInput[]): PackedBvh {
  return packBvhGroups([{ bvh, meshes }]);
}

/** A group of triangles with its own BVH (src/render/bvh/groups.ts): the world's, or a shared file's in object space. */
export interface BvhGroup {
  bvh: Bvh;
  meshes: BvhMeshInput[];
}

/**
 * Packs several BVHs into one texture: their triangles one after another
 * (group by group, BVH order within each), then the attribute blocks
 * (normals, texture coordinates, vertex colors), then the nodes. The first group's root is BVH_ROOT_NODE; each
 * group's root node is in `roots`.
 */
export function packBvhGroups(groups: BvhGroup[]): PackedBvh {
  const firstTriangle = [0];
  groups.forEach((g, i) => firstTriangle.push(firstTriangle[i] + g.bvh.triangleOrder.length));
  const n = firstTriangle[groups.length];
  const attributeTexels = groups.reduce((sum, g) => sum + g.meshes.reduce((s, m) => s + blockTexels(m) * (m.indices.length / 3), 0), 0);
  const attributesEnd = attributesStart(n) + attributeTexels;
  if (attributesEnd > BVH_MAX_TEXELS) {
    throw new Error(`${n} triangles exceed the BVH texture limit (${MAX_TRIANGLES} smooth textured triangles in total, ${MAX_COLORED_TRIANGLES} with vertex colors)`);
  }
  // Wide nodes: the first group's root at BVH_ROOT_NODE, every other (depth-first, group by group) from the row after the attributes, BVH_ROW_NODES to a row.
  const wides = groups.map(({ bvh }) => collapseBvh(bvh));
  const nodesStart = Math.ceil(attributesEnd / BVH_TEXTURE_WIDTH) * BVH_TEXTURE_WIDTH;
  const nodeTexel = (k: number) => nodesStart + Math.floor(k / BVH_ROW_NODES) * BVH_TEXTURE_WIDTH + (k % BVH_ROW_NODES) * BVH_NODE_TEXELS;
  let stored = 1;
  const slotBase = wides.map((w, g) => {
    const base = g === 0 ? -1 : stored - 1;
    stored += w.nodeCount - (g === 0 ? 1 : 0);
    return base;
  });
  // Wide node w of group g: the root of group 0 at BVH_ROOT_NODE, others the (base + w)th after the attributes.
  const texelOf = (g: number, w: number) => (g === 0 && w === 0 ? BVH_ROOT_NODE : nodeTexel(slotBase[g] + w));
  const texture = bvhTexture(Math.max(attributesEnd, stored > 1 ? nodeTexel(stored - 2) + BVH_NODE_TEXELS : 0));
  const out = texture.data;
  const bits = new Int32Array(out.buffer, out.byteOffset, out.length);

  groups.forEach(({ bvh }, g) => {
    const { nodeBounds, nodeData } = bvh;
    const { children, nodeCount, wideOf } = wides[g];
    for (let w = 0; w < nodeCount; w++) {
      const o = texelOf(g, w) * 4;
      for (let c = 0; c < BVH_WIDTH; c++) {
        const child = children[w * BVH_WIDTH + c];
        if (child < 0) continue; // an empty slot: its code stays 0.0
        // SoA: texel 2k holds the children's min along axis k, 2k + 1 their max.
        for (let k = 0; k < 3; k++) {
          out[o + 8 * k + c] = nodeBounds[child * 6 + k];
          out[o + 8 * k + 4 + c] = nodeBounds[child * 6 + 3 + k];
        }
        const count = nodeData[child * 2 + 1];
        const ref = count > 0 ? triangleTexel(firstTriangle[g] + nodeData[child * 2]) : texelOf(g, wideOf[child]);
        bits[o + 24 + c] = BVH_CODE_BIAS + ref * 16 + count;
      }
    }
  });

  const triangleOrder = new Uint32Array(n);
  let attributeTexel = attributesStart(n);
  let firstInput = 0;
  groups.forEach(({ bvh, meshes }, g) => {
    const meshOf = new Uint32Array(meshes.length + 1); // first input triangle of each mesh
    meshes.forEach((m, i) => (meshOf[i + 1] = meshOf[i] + m.indices.length / 3));
    let mesh = 0;
    for (let j = 0; j < bvh.triangleOrder.length; j++) {
      const id = bvh.triangleOrder[j];
      const at = firstTriangle[g] + j;
      triangleOrder[at] = firstInput + id;
      mesh = findMesh(meshOf, id, mesh);
      const { positions, normals, uvs, colors, indices, material = 0 } = meshes[mesh];
      const local = (id - meshOf[mesh]) * 3;
      const o = triangleTexel(at) * 4;
      // A flat colored triangle keeps a (zero) uv block: its second texel says the colors follow.
      const uvBlock = !!uvs || (!!colors && !normals);
      const uvTexel = attributeTexel + (normals ? NORMAL_TEXELS : 0);
      const colorTexel = uvTexel + (uvBlock ? UV_TEXELS : 0);
      for (let c = 0; c < 3; c++) {
        const v = indices[local + c];
        for (let k = 0; k < 3; k++) out[o + c * 4 + k] = positions[v * 3 + k];
        if (normals) for (let k = 0; k < 3; k++) out[attributeTexel * 4 + c * 4 + k] = normals[v * 3 + k];
        if (uvs) for (let k = 0; k < 2; k++) out[uvTexel * 4 + c * 2 + k] = uvs[v * 2 + k];
        if (colors) for (let k = 0; k < 3; k++) out[(colorTexel + c) * 4 + k] = colors[v * 3 + k];
      }
      if (normals && uvs) out[attributeTexel * 4 + 3] = 1;
      if (colors) out[normals ? attributeTexel * 4 + 7 : (uvTexel + 1) * 4 + 2] = 1;
      out[o + 3] = material;
      out[o + 7] = normals ? attributeTexel : uvBlock ? -2 - attributeTexel : -1;
      out[o + 11] = meshes[mesh].mesh ?? mesh;
      attributeTexel += blockTexels(meshes[mesh]);
    }
    firstInput += meshOf[meshes.length];
  });
  const roots = groups.map((_, g) => texelOf(g, 0));
  // Roots travel as float values (the instance table): exact below 2^24.
  if (roots.some((r) => r >= BVH_MAX_TEXELS)) throw new Error(`a BVH group's root node is past texel 2^24 (${n} triangles)`);
  const depth = groups.reduce((d, g) => Math.max(d, g.bvh.depth), 0);
  const stackEntries = wides.reduce((d, w) => Math.max(d, w.stackEntries), 0);
  return { texture, nodeCount: stored, triangleCount: n, triangleOrder, depth, stackEntries, roots };
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

/** A child of a wide node: its box, and a leaf's first triangle's texel and triangle count, or a child node's texel (count 0). */
export interface WideChild {
  lo: [number, number, number];
  hi: [number, number, number];
  ref: number;
  count: number;
}

/** The 4 child slots of the node at `texel` (bvh.glsl's decoding); null for an empty slot. */
export function nodeChildren(data: Float32Array, texel: number): (WideChild | null)[] {
  const o = texel * 4;
  const codes = new Int32Array(data.buffer, data.byteOffset + (o + 24) * 4, 4);
  return [0, 1, 2, 3].map((c) => {
    const code = codes[c] - BVH_CODE_BIAS;
    if (code < 0) return null;
    const axis = (k: number, hi: number) => data[o + 8 * k + 4 * hi + c];
    return { lo: [axis(0, 0), axis(1, 0), axis(2, 0)], hi: [axis(0, 1), axis(1, 1), axis(2, 1)], ref: code >> 4, count: code & 15 };
  });
}

/** The box around everything: the union of the root's children's boxes (min xyz, max xyz). */
export function bvhBounds(packed: PackedBvh): [number[], number[]] {
  const used = nodeChildren(packed.texture.data, BVH_ROOT_NODE).filter((c): c is WideChild => c !== null);
  return [[0, 1, 2].map((k) => Math.min(...used.map((c) => c.lo[k]))), [0, 1, 2].map((k) => Math.max(...used.map((c) => c.hi[k])))];
}
