/**
 * Wavefront OBJ: `v`, `vt`, `vn` and `f` lines (any polygon,
 * fan-triangulated; 1-based or negative relative indices; `v/vt/vn`,
 * `v//vn`, `v/vt`, `v`). Everything else (groups, materials, lines) is
 * ignored. The mesh is smooth only if every face corner references a
 * normal, and has texture coordinates only if every corner references a
 * `vt` (v turned over, `v' = 1 - v`, as Mitsuba's OBJ loader does: OBJ counts
 * v up from the bottom of the image). Then there is one vertex per distinct
 * (position, coordinates, normal) a corner names.
 */
import { AssetError } from '../assetError';
import type { TriangleMesh } from '../types';
import { finalizeMesh } from './finalize';

interface Corner {
  v: number;
  vt: number; // -1 when the corner names no texture coordinates
  vn: number; // -1 when the corner names no normal
}

export function decodeObj(bytes: Uint8Array): TriangleMesh {
  const text = new TextDecoder('utf-8', { fatal: false }).decode(bytes);
  const positions: number[] = [];
  const normals: number[] = [];
  const uvs: number[] = []; // 2 per `vt`, v already turned over
  const corners: Corner[] = []; // 3 per triangle
  const lines = text.split(/\r?\n/);
  for (let n = 0; n < lines.length; n++) {
    const line = lines[n].trim();
    if (line === '' || line[0] === '#') continue;
    const fields = line.split(/\s+/);
    const keyword = fields[0];
    if (keyword === 'v' || keyword === 'vn') {
      if (fields.length < 4) throw new AssetError(`line ${n + 1}: "${keyword}" needs 3 numbers`);
      const xyz = [Number(fields[1]), Number(fields[2]), Number(fields[3])];
      if (keyword === 'v' && !xyz.every(Number.isFinite)) throw new AssetError(`line ${n + 1}: vertex ${positions.length / 3} has a non-finite coordinate`);
      (keyword === 'v' ? positions : normals).push(...xyz);
    } else if (keyword === 'vt') {
      // `vt u [v [w]]`: v defaults to 0; w (3D textures) is ignored.
      if (fields.length < 2) throw new AssetError(`line ${n + 1}: "vt" needs at least 1 number`);
      const uv = [Number(fields[1]), fields.length > 2 ? Number(fields[2]) : 0];
      if (!uv.every(Number.isFinite)) throw new AssetError(`line ${n + 1}: texture coordinate ${uvs.length / 2} is not finite`);
      uvs.push(uv[0], 1 - uv[1]);
    } else if (keyword === 'f') {
      const face = fields.slice(1).map((field) => parseCorner(field, positions.length / 3, uvs.length / 2, normals.length / 3, n + 1));
      if (face.length < 3) throw new AssetError(`line ${n + 1}: a face needs at least 3 corners`);
      for (let i = 1; i + 1 < face.length; i++) corners.push(face[0], face[i], face[i + 1]);
    }
  }
  if (corners.length === 0) throw new AssetError('the file has no faces (not an OBJ file?)');
  const smooth = corners.every((c) => c.vn >= 0);
  const textured = corners.every((c) => c.vt >= 0);
  if (!smooth && !textured) return finalizeMesh({ positions, normals: null, indices: corners.map((c) => c.v), uvs: null });
  return deindexedMesh(positions, smooth ? normals : null, textured ? uvs : null, corners);
}

function parseCorner(field: string, vertexCount: number, uvCount: number, normalCount: number, line: number): Corner {
  const parts = field.split('/');
  const v = resolveIndex(parts[0], vertexCount, line, 'vertex');
  const vt = parts.length >= 2 && parts[1] !== '' ? resolveIndex(parts[1], uvCount, line, 'texture coordinate') : -1;
  const vn = parts.length >= 3 && parts[2] !== '' ? resolveIndex(parts[2], normalCount, line, 'normal') : -1;
  return { v, vt, vn };
}

/** 1-based, or negative = relative to the end of the list so far. */
function resolveIndex(text: string, count: number, line: number, what: string): number {
  const value = Number(text);
  if (!Number.isInteger(value) || value === 0) throw new AssetError(`line ${line}: "${text}" is not a valid ${what} index`);
  const index = value > 0 ? value - 1 : count + value;
  if (index < 0 || index >= count) throw new AssetError(`line ${line}: ${what} index ${value} is out of range (${count} defined so far)`);
  return index;
}

/**
 * One output vertex per distinct (position, coordinates, normal) a corner
 * names, of the attributes kept (a null `normals` or `uvs` is left out of the
 * key and of the output).
 */
function deindexedMesh(positions: number[], normals: number[] | null, uvs: number[] | null, corners: Corner[]): TriangleMesh {
  // Two steps, so that no key exceeds 2^53: (v, vt) -> pair id, then (pair id, vn) -> vertex.
  const pairOf = new Map<number, number>();
  const vertexOf = new Map<number, number>();
  const outPositions: number[] = [];
  const outNormals: number[] | null = normals ? [] : null;
  const outUvs: number[] | null = uvs ? [] : null;
  const uvCount = uvs ? uvs.length / 2 : 1;
  const normalCount = normals ? normals.length / 3 : 1;
  const indices = corners.map(({ v, vt, vn }) => {
    const pairKey = v * uvCount + (uvs ? vt : 0);
    let pair = pairOf.get(pairKey);
    if (pair === undefined) {
      pair = pairOf.size;
      pairOf.set(pairKey, pair);
    }
    const key = pair * normalCount + (normals ? vn : 0);
    let index = vertexOf.get(key);
    if (index === undefined) {
      index = outPositions.length / 3;
      vertexOf.set(key, index);
      outPositions.push(positions[v * 3], positions[v * 3 + 1], positions[v * 3 + 2]);
      if (outNormals && normals) outNormals.push(normals[vn * 3], normals[vn * 3 + 1], normals[vn * 3 + 2]);
      if (outUvs && uvs) outUvs.push(uvs[vt * 2], uvs[vt * 2 + 1]);
    }
    return index;
  });
  return finalizeMesh({ positions: outPositions, normals: outNormals, indices, uvs: outUvs });
}
