/**
 * Wavefront OBJ: `v`, `vt`, `vn` and `f` lines (any polygon,
 * fan-triangulated; 1-based or negative relative indices; `v/vt/vn`,
 * `v//vn`, `v/vt`, `v`), and `mtllib`/`usemtl` (below). Everything else
 * (groups, lines, smoothing groups) is ignored. The mesh is smooth only if
 * every face corner references a normal, and has texture coordinates only if
 * every corner references a `vt` (v turned over, `v' = 1 - v`, as Mitsuba's
 * OBJ loader does: OBJ counts v up from the bottom of the image). Then there
 * is one vertex per distinct (position, coordinates, normal) a corner names.
 *
 * Materials: the MTL files `mtllib` names (paths relative to the OBJ's
 * folder) are read through `resolveResource`, which takes URIs as for a
 * glTF's buffers (the name is percent-encoded; `\` read as `/`). Faces after
 * `usemtl name` get that material (mtl.ts), faces before any `usemtl` or
 * naming a material no MTL defines the default principled material. Without
 * any `mtllib` or `usemtl` the mesh has no `fileMaterials` (as before MTL
 * support); an MTL that cannot be read is a warning, never an error, and
 * when none could be read the mesh has no file materials either.
 */
import { AssetError } from '../assetError';
import type { Material } from '../../materials/registry';
import type { FileMaterial, FileMaterials, TriangleMesh } from '../types';
import { finalizeMesh, type RawMesh } from './finalize';
import type { ResourceResolver } from './gltf';
import { defaultPrincipled, joinPath, parseMtl } from './mtl';

interface Corner {
  v: number;
  vt: number; // -1 when the corner names no texture coordinates
  vn: number; // -1 when the corner names no normal
}

/** What the OBJ text says, before materials are looked up. */
interface ObjData {
  positions: number[];
  normals: number[];
  uvs: number[]; // 2 per `vt`, v already turned over
  corners: Corner[]; // 3 per triangle
  /** The rest of each `mtllib` line, as written. */
  mtllibs: string[];
  /** The `usemtl` names, in order of first appearance. */
  groupNames: string[];
  /** Per triangle, its index in `groupNames`, -1 before any `usemtl` (or after an empty one). */
  triangleGroups: number[];
}

export async function decodeObj(bytes: Uint8Array, resolveResource?: ResourceResolver): Promise<TriangleMesh> {
  const obj = parseObj(new TextDecoder('utf-8', { fatal: false }).decode(bytes));
  if (obj.mtllibs.length === 0 && obj.groupNames.length === 0) return finalizeMesh(rawMesh(obj));
  const warnings: string[] = [];
  const fileMaterials = await objMaterials(obj, resolveResource, warnings);
  const mesh = finalizeMesh({ ...rawMesh(obj), fileMaterials });
  if (!fileMaterials) mesh.fileMaterials = null;
  if (warnings.length > 0) mesh.warnings = warnings;
  return mesh;
}

function parseObj(text: string): ObjData {
  const obj: ObjData = { positions: [], normals: [], uvs: [], corners: [], mtllibs: [], groupNames: [], triangleGroups: [] };
  const { positions, normals, uvs, corners } = obj;
  const groupOf = new Map<string, number>();
  let group = -1;
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
      for (let i = 1; i + 1 < face.length; i++) {
        corners.push(face[0], face[i], face[i + 1]);
        obj.triangleGroups.push(group);
      }
    } else if (keyword === 'mtllib' && fields.length > 1) {
      obj.mtllibs.push(fields.slice(1).join(' '));
    } else if (keyword === 'usemtl') {
      const name = fields.slice(1).join(' ');
      if (name !== '' && !groupOf.has(name)) {
        groupOf.set(name, obj.groupNames.length);
        obj.groupNames.push(name);
      }
      group = name === '' ? -1 : groupOf.get(name)!;
    }
  }
  if (corners.length === 0) throw new AssetError('the file has no faces (not an OBJ file?)');
  return obj;
}

/** The triangles, smooth and textured where every corner allows it. */
function rawMesh({ positions, normals, uvs, corners }: ObjData): RawMesh {
  const smooth = corners.every((c) => c.vn >= 0);
  const textured = corners.every((c) => c.vt >= 0);
  if (!smooth && !textured) return { positions, normals: null, indices: corners.map((c) => c.v), uvs: null };
  return deindexedMesh(positions, smooth ? normals : null, textured ? uvs : null, corners);
}

/**
 * The materials of the MTL files (null when none could be read), one per
 * `usemtl` name that one defines, and the default principled material for
 * the other triangles; `triangles` has one entry per triangle of `obj`.
 */
async function objMaterials(obj: ObjData, resolveResource: ResourceResolver | undefined, warnings: string[]): Promise<FileMaterials | null> {
  if (obj.mtllibs.length === 0) warnings.push('usemtl without mtllib: the default material');
  const library = await readLibraries(obj.mtllibs, resolveResource, warnings);
  if (!library) return null;
  for (const name of obj.groupNames) {
    if (!library.has(name)) warnings.push(`usemtl "${name}": no MTL file defines it: the default material`);
  }
  if (obj.groupNames.length >= 0x10000) throw new AssetError(`the file names ${obj.groupNames.length} materials (usemtl), more than ${0x10000 - 1}`);
  // Materials are numbered in the order the faces first use them.
  const materials: FileMaterial[] = [];
  const indexOf = new Map<string | null, number>();
  const materialIndex = (name: string | null): number => {
    let index = indexOf.get(name);
    if (index !== undefined) return index;
    index = materials.length;
    indexOf.set(name, index);
    materials.push({ name: name ?? '', material: name === null ? defaultPrincipled() : library.get(name)!, uvSet: 0, vertexColors: false });
    return index;
  };
  const triangles = new Uint16Array(obj.triangleGroups.length);
  for (let t = 0; t < triangles.length; t++) {
    const name = obj.triangleGroups[t] >= 0 ? obj.groupNames[obj.triangleGroups[t]] : null;
    triangles[t] = materialIndex(name !== null && library.has(name) ? name : null);
  }
  return { materials, triangles, images: new Map() };
}

/** Every material of the MTL files the `mtllib` lines name, by name (a later file's wins); null when no file could be read. */
async function readLibraries(mtllibs: string[], resolveResource: ResourceResolver | undefined, warnings: string[]): Promise<Map<string, Material> | null> {
  const library = new Map<string, Material>();
  let read = 0;
  for (const line of mtllibs) {
    for (const { path, text } of await mtlFiles(line, resolveResource)) {
      if (text === null) {
        warnings.push(`${path} not found: the default material`);
        continue;
      }
      read++;
      const mtl = parseMtl(text, path);
      warnings.push(...mtl.warnings);
      for (const [name, material] of mtl.materials) library.set(name, material);
    }
  }
  return read > 0 ? library : null;
}

/**
 * The MTL files one `mtllib` line names, each with its text (null when it
 * cannot be read). The whole line is tried first, as one name with spaces;
 * if that cannot be read and it has several words, each word is one file
 * (the format's list of names).
 */
async function mtlFiles(line: string, resolveResource: ResourceResolver | undefined): Promise<{ path: string; text: string | null }[]> {
  const whole = { path: joinPath('', line), text: await readText(joinPath('', line), resolveResource) };
  const words = line.split(' ');
  if (whole.text !== null || words.length === 1) return [whole];
  return Promise.all(words.map(async (word) => ({ path: joinPath('', word), text: await readText(joinPath('', word), resolveResource) })));
}

async function readText(path: string, resolveResource: ResourceResolver | undefined): Promise<string | null> {
  if (!resolveResource) return null;
  try {
    const uri = path.split('/').map(encodeURIComponent).join('/');
    return new TextDecoder('utf-8', { fatal: false }).decode(await resolveResource(uri));
  } catch {
    return null;
  }
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
function deindexedMesh(positions: number[], normals: number[] | null, uvs: number[] | null, corners: Corner[]): RawMesh {
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
  return { positions: outPositions, normals: outNormals, indices, uvs: outUvs };
}
