/**
 * The checks every mesh decoder ends with: finite vertices, normals,
 * texture coordinates and tangents (one per vertex), indices in range,
 * degenerate (zero-area) triangles dropped (with their entries of the
 * per-triangle material indices), at least one triangle left. Decoders build
 * raw arrays; this turns them into a TriangleMesh or throws an AssetError
 * saying what is wrong.
 */
import { AssetError } from '../assetError';
import type { FileMaterials, TriangleMesh } from '../types';

export interface RawMesh {
  positions: ArrayLike<number>;
  /** 3 per vertex, or null when the file does not give a normal for every corner. */
  normals: ArrayLike<number> | null;
  indices: ArrayLike<number>;
  /** 2 per vertex (u, v), the file's first set; null or absent when the file does not give one for every vertex. */
  uvs?: ArrayLike<number> | null;
  /** 2 per vertex, a second set (glTF TEXCOORD_1); null or absent when there is none. */
  uvs1?: ArrayLike<number> | null;
  /** 4 per vertex (glTF TANGENT, xyz and w), (0, 0, 0, 0) where none is given; null or absent when there is none. */
  tangents?: ArrayLike<number> | null;
  /** 3 per vertex, linear RGB (glTF COLOR_0); null or absent when there is none. */
  colors?: ArrayLike<number> | null;
  /** The file's own materials, `triangles` one entry per triangle of `indices` (compacted with them). */
  fileMaterials?: RawFileMaterials | null;
}

type RawFileMaterials = Omit<FileMaterials, 'triangles'> & { triangles: ArrayLike<number> };

export function finalizeMesh(raw: RawMesh): TriangleMesh {
  const vertexCount = Math.floor(raw.positions.length / 3);
  const positions = Float32Array.from(raw.positions);
  for (let i = 0; i < positions.length; i++) {
    if (!Number.isFinite(positions[i])) throw new AssetError(`vertex ${Math.floor(i / 3)} has a non-finite coordinate (${raw.positions[i]})`);
  }
  const normals = raw.normals ? normalizedNormals(raw.normals, vertexCount) : null;
  // Vertices are never reindexed here (triangles are only dropped), so per-vertex arrays stay aligned.
  const uvs = raw.uvs ? checkedUvs(raw.uvs, vertexCount, 'texture coordinate') : null;
  const uvs1 = raw.uvs1 ? checkedUvs(raw.uvs1, vertexCount, 'second texture coordinate (TEXCOORD_1)') : null;
  const tangents = raw.tangents ? normalizedTangents(raw.tangents, vertexCount) : null;
  const colors = raw.colors ? checkedColors(raw.colors, vertexCount) : null;
  if (raw.indices.length % 3 !== 0) throw new AssetError(`the index count ${raw.indices.length} is not a multiple of 3`);
  const materials = raw.fileMaterials ? checkedTriangleMaterials(raw.fileMaterials, raw.indices.length / 3) : null;
  const kept = new Uint32Array(raw.indices.length);
  let keptCount = 0;
  for (let t = 0; t < raw.indices.length; t += 3) {
    const a = raw.indices[t];
    const b = raw.indices[t + 1];
    const c = raw.indices[t + 2];
    for (const index of [a, b, c]) {
      if (!Number.isInteger(index) || index < 0 || index >= vertexCount) {
        throw new AssetError(`triangle ${t / 3} references vertex ${index}, but the file has ${vertexCount} vertices`);
      }
    }
    if (isDegenerate(positions, a, b, c)) continue; // zero area: no surface to hit
    if (materials) materials[keptCount / 3] = materials[t / 3]; // keptCount / 3 <= t / 3: read before it is overwritten
    kept[keptCount++] = a;
    kept[keptCount++] = b;
    kept[keptCount++] = c;
  }
  if (raw.indices.length === 0) throw new AssetError('the file has no triangles');
  if (keptCount === 0) throw new AssetError('every triangle of the file has zero area');
  const mesh: TriangleMesh = { positions, normals, indices: kept.slice(0, keptCount), uvs, uvs1, tangents };
  if (colors) mesh.colors = colors;
  if (materials) mesh.fileMaterials = { ...raw.fileMaterials!, triangles: materials.slice(0, keptCount / 3) };
  return mesh;
}

/** 3 finite floats per vertex. */
function checkedColors(source: ArrayLike<number>, vertexCount: number): Float32Array {
  if (source.length !== vertexCount * 3) throw new AssetError(`the file gives ${source.length / 3} vertex colors for ${vertexCount} vertices`);
  const colors = Float32Array.from(source);
  for (let i = 0; i < colors.length; i++) if (!Number.isFinite(colors[i])) throw new AssetError(`vertex ${Math.floor(i / 3)} has a non-finite color`);
  return colors;
}

/** A copy of the per-triangle material indices (compacted in place as triangles are dropped), checked against the triangle and material counts. */
function checkedTriangleMaterials(fileMaterials: RawFileMaterials, triangleCount: number): Uint16Array {
  const { triangles, materials } = fileMaterials;
  if (triangles.length !== triangleCount) throw new AssetError(`the file gives materials for ${triangles.length} of its ${triangleCount} triangles`);
  for (let t = 0; t < triangles.length; t++) {
    if (triangles[t] >= materials.length) throw new AssetError(`triangle ${t} has material ${triangles[t]}, but the file has ${materials.length} materials`);
  }
  return Uint16Array.from(triangles);
}

/**
 * Unit xyz and w = +-1 (its sign). A zero xyz or a zero w says nothing about
 * the frame: that vertex gets (0, 0, 0, 0), none given (MikkTSpace fills it in).
 */
function normalizedTangents(source: ArrayLike<number>, vertexCount: number): Float32Array {
  if (source.length !== vertexCount * 4) throw new AssetError(`the file gives ${source.length / 4} tangents for ${vertexCount} vertices`);
  const tangents = new Float32Array(vertexCount * 4);
  for (let v = 0; v < vertexCount; v++) {
    const x = source[v * 4];
    const y = source[v * 4 + 1];
    const z = source[v * 4 + 2];
    const w = source[v * 4 + 3];
    if (!Number.isFinite(x) || !Number.isFinite(y) || !Number.isFinite(z) || !Number.isFinite(w)) throw new AssetError(`vertex ${v} has a non-finite tangent`);
    const length = Math.hypot(x, y, z);
    if (length === 0 || w === 0) continue;
    tangents[v * 4] = x / length;
    tangents[v * 4 + 1] = y / length;
    tangents[v * 4 + 2] = z / length;
    tangents[v * 4 + 3] = Math.sign(w);
  }
  return tangents;
}

/** 2 finite floats per vertex, exactly one pair per vertex. */
function checkedUvs(source: ArrayLike<number>, vertexCount: number, what: string): Float32Array {
  if (source.length !== vertexCount * 2) throw new AssetError(`the file gives ${source.length / 2} ${what} pairs for ${vertexCount} vertices`);
  const uvs = Float32Array.from(source);
  for (let i = 0; i < uvs.length; i++) {
    if (!Number.isFinite(uvs[i])) throw new AssetError(`vertex ${Math.floor(i / 2)} has a non-finite ${what} (${source[i]})`);
  }
  return uvs;
}

/** Unit normals; a zero normal stays zero (the shader then falls back to the face normal). */
function normalizedNormals(source: ArrayLike<number>, vertexCount: number): Float32Array {
  if (source.length < vertexCount * 3) throw new AssetError(`the file gives ${Math.floor(source.length / 3)} normals for ${vertexCount} vertices`);
  const normals = new Float32Array(vertexCount * 3);
  for (let v = 0; v < vertexCount; v++) {
    const x = source[v * 3];
    const y = source[v * 3 + 1];
    const z = source[v * 3 + 2];
    if (!Number.isFinite(x) || !Number.isFinite(y) || !Number.isFinite(z)) throw new AssetError(`vertex ${v} has a non-finite normal`);
    const length = Math.hypot(x, y, z);
    const scale = length > 0 ? 1 / length : 0;
    normals[v * 3] = x * scale;
    normals[v * 3 + 1] = y * scale;
    normals[v * 3 + 2] = z * scale;
  }
  return normals;
}

/** cross(p[b] - p[a], p[c] - p[a]) in double precision: twice the triangle's area along its winding's normal. */
export function triangleCross(p: Float32Array, a: number, b: number, c: number): [number, number, number] {
  const e1x = p[b * 3] - p[a * 3];
  const e1y = p[b * 3 + 1] - p[a * 3 + 1];
  const e1z = p[b * 3 + 2] - p[a * 3 + 2];
  const e2x = p[c * 3] - p[a * 3];
  const e2y = p[c * 3 + 1] - p[a * 3 + 1];
  const e2z = p[c * 3 + 2] - p[a * 3 + 2];
  return [e1y * e2z - e1z * e2y, e1z * e2x - e1x * e2z, e1x * e2y - e1y * e2x];
}

/** Exactly zero area (in double precision over the float32 coordinates), repeated vertices included. */
function isDegenerate(p: Float32Array, a: number, b: number, c: number): boolean {
  if (a === b || b === c || a === c) return true;
  const [x, y, z] = triangleCross(p, a, b, c);
  return x === 0 && y === 0 && z === 0;
}
