/**
 * Wavefront OBJ: `v`, `vn` and `f` lines (any polygon, fan-triangulated;
 * 1-based or negative relative indices; `v/vt/vn`, `v//vn`, `v/vt`, `v`).
 * Everything else (groups, materials, texture coordinates, lines) is ignored.
 * The mesh is smooth only if every face corner references a normal.
 */
import { AssetError } from '../assetError';
import type { TriangleMesh } from '../types';
import { finalizeMesh } from './finalize';

interface Corner {
  v: number;
  vn: number; // -1 when the corner names no normal
}

export function decodeObj(bytes: Uint8Array): TriangleMesh {
  const text = new TextDecoder('utf-8', { fatal: false }).decode(bytes);
  const positions: number[] = [];
  const normals: number[] = [];
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
    } else if (keyword === 'f') {
      const face = fields.slice(1).map((field) => parseCorner(field, positions.length / 3, normals.length / 3, n + 1));
      if (face.length < 3) throw new AssetError(`line ${n + 1}: a face needs at least 3 corners`);
      for (let i = 1; i + 1 < face.length; i++) corners.push(face[0], face[i], face[i + 1]);
    }
  }
  if (corners.length === 0) throw new AssetError('the file has no faces (not an OBJ file?)');
  const smooth = corners.every((c) => c.vn >= 0);
  return smooth ? smoothMesh(positions, normals, corners) : finalizeMesh({ positions, normals: null, indices: corners.map((c) => c.v) });
}

function parseCorner(field: string, vertexCount: number, normalCount: number, line: number): Corner {
  const parts = field.split('/');
  const v = resolveIndex(parts[0], vertexCount, line, 'vertex');
  const vn = parts.length >= 3 && parts[2] !== '' ? resolveIndex(parts[2], normalCount, line, 'normal') : -1;
  return { v, vn };
}

/** 1-based, or negative = relative to the end of the list so far. */
function resolveIndex(text: string, count: number, line: number, what: string): number {
  const value = Number(text);
  if (!Number.isInteger(value) || value === 0) throw new AssetError(`line ${line}: "${text}" is not a valid ${what} index`);
  const index = value > 0 ? value - 1 : count + value;
  if (index < 0 || index >= count) throw new AssetError(`line ${line}: ${what} index ${value} is out of range (${count} defined so far)`);
  return index;
}

/** One output vertex per distinct (position, normal) pair. */
function smoothMesh(positions: number[], normals: number[], corners: Corner[]): TriangleMesh {
  const vertexOf = new Map<number, number>();
  const outPositions: number[] = [];
  const outNormals: number[] = [];
  const normalCount = normals.length / 3;
  const indices = corners.map(({ v, vn }) => {
    const key = v * normalCount + vn;
    let index = vertexOf.get(key);
    if (index === undefined) {
      index = outPositions.length / 3;
      vertexOf.set(key, index);
      outPositions.push(positions[v * 3], positions[v * 3 + 1], positions[v * 3 + 2]);
      outNormals.push(normals[vn * 3], normals[vn * 3 + 1], normals[vn * 3 + 2]);
    }
    return index;
  });
  return finalizeMesh({ positions: outPositions, normals: outNormals, indices });
}
