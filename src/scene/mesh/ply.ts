/**
 * Stanford PLY: ASCII, binary little- and big-endian. Reads the `vertex`
 * element (x y z, and nx ny nz when all three are present: the mesh is then
 * smooth; texture coordinates as stored from `u v`, else `s t`, else
 * `texture_u texture_v`, of any numeric type) and the `face` element (a
 * list property `vertex_indices` or `vertex_index`, any polygon,
 * fan-triangulated); other elements and
 * properties are read past. A header that promises more data than the file
 * holds is an error.
 */
import { AssetError } from '../assetError';
import type { TriangleMesh } from '../types';
import { finalizeMesh } from './finalize';

type Format = 'ascii' | 'binary_little_endian' | 'binary_big_endian';

interface Property {
  name: string;
  type: string;
  /** The count type of a list property; undefined for a scalar. */
  countType?: string;
}

interface Element {
  name: string;
  count: number;
  properties: Property[];
}

const SIZES: Record<string, number> = {
  char: 1, int8: 1, uchar: 1, uint8: 1, short: 2, int16: 2, ushort: 2, uint16: 2,
  int: 4, int32: 4, uint: 4, uint32: 4, float: 4, float32: 4, double: 8, float64: 8,
};

interface Header {
  format: Format;
  elements: Element[];
  dataStart: number;
}

export function decodePly(bytes: Uint8Array): TriangleMesh {
  const header = parseHeader(bytes);
  const read = header.format === 'ascii' ? asciiReader(bytes, header.dataStart) : binaryReader(bytes, header.dataStart, header.format === 'binary_little_endian');
  const positions: number[] = [];
  let normals: number[] | null = null;
  let uvs: number[] | null = null;
  const indices: number[] = [];
  for (const element of header.elements) {
    if (element.name === 'vertex') ({ normals, uvs } = readVertices(element, read, positions));
    else if (element.name === 'face') readFaces(element, read, indices);
    else skipElement(element, read);
  }
  if (!header.elements.some((e) => e.name === 'vertex')) throw new AssetError('the PLY header declares no vertex element');
  if (!header.elements.some((e) => e.name === 'face')) throw new AssetError('the file has no triangles (no face element)');
  return finalizeMesh({ positions, normals, indices, uvs });
}

function parseHeader(bytes: Uint8Array): Header {
  const head = new TextDecoder('latin1').decode(bytes.subarray(0, Math.min(bytes.length, 65536)));
  const end = /end_header\r?\n/.exec(head);
  if (!head.startsWith('ply') || !end) throw new AssetError('not a PLY file (no "ply ... end_header" header)');
  const lines = head.slice(0, end.index).split(/\r?\n/).map((l) => l.trim()).filter((l) => l !== '');
  let format: Format | null = null;
  const elements: Element[] = [];
  for (const line of lines.slice(1)) {
    const f = line.split(/\s+/);
    if (f[0] === 'format') {
      if (f[1] !== 'ascii' && f[1] !== 'binary_little_endian' && f[1] !== 'binary_big_endian') throw new AssetError(`unknown PLY format "${f[1]}"`);
      format = f[1];
    } else if (f[0] === 'element') {
      const count = Number(f[2]);
      if (!Number.isInteger(count) || count < 0) throw new AssetError(`PLY element "${f[1]}" has an invalid count "${f[2]}"`);
      elements.push({ name: f[1], count, properties: [] });
    } else if (f[0] === 'property') {
      const element = elements[elements.length - 1];
      if (!element) throw new AssetError('a PLY property comes before any element');
      const property: Property = f[1] === 'list' ? { name: f[4], type: f[3], countType: f[2] } : { name: f[2], type: f[1] };
      for (const type of [property.type, property.countType]) {
        if (type !== undefined && !(type in SIZES)) throw new AssetError(`PLY property "${property.name}" has an unknown type "${type}"`);
      }
      element.properties.push(property);
    }
  }
  if (!format) throw new AssetError('the PLY header has no format line');
  return { format, elements, dataStart: end.index + end[0].length };
}

/** Reads the next value of a type; throws when the data ends early. */
type Reader = (type: string) => number;

function truncated(): never {
  throw new AssetError('the file ends before the data its PLY header declares (truncated or lying header)');
}

function asciiReader(bytes: Uint8Array, start: number): Reader {
  const tokens = new TextDecoder('latin1').decode(bytes.subarray(start)).split(/\s+/).filter((t) => t !== '');
  let next = 0;
  return () => {
    if (next >= tokens.length) truncated();
    const token = tokens[next++];
    // Some writers spell non-finite values out; they are then reported as such.
    const special = /^([-+]?)(nan|inf|infinity)$/i.exec(token);
    if (special) return special[2].toLowerCase() === 'nan' ? NaN : special[1] === '-' ? -Infinity : Infinity;
    const value = Number(token);
    if (Number.isNaN(value)) throw new AssetError(`"${token}" in the PLY data is not a number`);
    return value;
  };
}

function binaryReader(bytes: Uint8Array, start: number, little: boolean): Reader {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  let offset = start;
  return (type) => {
    const size = SIZES[type];
    if (offset + size > bytes.length) truncated();
    const at = offset;
    offset += size;
    switch (type) {
      case 'char': case 'int8': return view.getInt8(at);
      case 'uchar': case 'uint8': return view.getUint8(at);
      case 'short': case 'int16': return view.getInt16(at, little);
      case 'ushort': case 'uint16': return view.getUint16(at, little);
      case 'int': case 'int32': return view.getInt32(at, little);
      case 'uint': case 'uint32': return view.getUint32(at, little);
      case 'float': case 'float32': return view.getFloat32(at, little);
      default: return view.getFloat64(at, little);
    }
  };
}

/** The spellings of texture coordinates, in the order they are looked for. */
const UV_NAMES = [['u', 'v'], ['s', 't'], ['texture_u', 'texture_v']] as const;

/** Appends x y z per vertex to `positions`; returns the normals when nx ny nz are all present, the coordinates when a pair of UV_NAMES is. */
function readVertices(element: Element, read: Reader, positions: number[]): { normals: number[] | null; uvs: number[] | null } {
  const names = element.properties.map((p) => p.name);
  const slot = (name: string) => names.indexOf(name);
  const xyz = ['x', 'y', 'z'].map(slot);
  if (xyz.some((i) => i < 0)) throw new AssetError('the PLY vertex element lacks x, y or z');
  const nxyz = ['nx', 'ny', 'nz'].map(slot);
  const normals = nxyz.every((i) => i >= 0) ? [] as number[] : null;
  const uv = UV_NAMES.map((pair) => pair.map(slot)).find((pair) => pair.every((i) => i >= 0)) ?? null;
  const uvs = uv ? [] as number[] : null;
  const values = new Array<number>(names.length).fill(0);
  for (let v = 0; v < element.count; v++) {
    element.properties.forEach((p, i) => {
      values[i] = p.countType ? skipList(p, read) : read(p.type);
    });
    positions.push(values[xyz[0]], values[xyz[1]], values[xyz[2]]);
    normals?.push(values[nxyz[0]], values[nxyz[1]], values[nxyz[2]]);
    if (uv) uvs?.push(values[uv[0]], values[uv[1]]);
  }
  return { normals, uvs };
}

function readFaces(element: Element, read: Reader, indices: number[]): void {
  const listIndex = element.properties.findIndex((p) => p.countType && (p.name === 'vertex_indices' || p.name === 'vertex_index'));
  if (listIndex < 0) throw new AssetError('the PLY face element has no vertex_indices list');
  for (let f = 0; f < element.count; f++) {
    element.properties.forEach((p, i) => {
      if (i !== listIndex) {
        if (p.countType) skipList(p, read);
        else read(p.type);
        return;
      }
      const count = read(p.countType!);
      const face: number[] = [];
      for (let k = 0; k < count; k++) face.push(read(p.type));
      if (count < 3) throw new AssetError(`PLY face ${f} has ${count} corners (at least 3 needed)`);
      for (let k = 1; k + 1 < count; k++) indices.push(face[0], face[k], face[k + 1]);
    });
  }
}

function skipList(p: Property, read: Reader): number {
  const count = read(p.countType!);
  if (!Number.isInteger(count) || count < 0) throw new AssetError(`PLY list "${p.name}" has an invalid length ${count}`);
  for (let k = 0; k < count; k++) read(p.type);
  return 0;
}

function skipElement(element: Element, read: Reader): void {
  for (let e = 0; e < element.count; e++) {
    for (const p of element.properties) {
      if (p.countType) skipList(p, read);
      else read(p.type);
    }
  }
}
