/**
 * Reader for OIDN's TZA weight files (format version 2): a table of named
 * tensors, each with dims, a layout string ("oihw" for convolution weights,
 * "x" for biases) and float16 or float32 data. Layout of the file, from
 * OIDN's core/tza.cpp: magic 0x41D7 (u16), major 2 (u8), minor (u8), table
 * offset (u64); at the table: count (u32), then per tensor a name (u16
 * length + bytes), ndims (u8), dims (u32 each), layout (ndims chars),
 * data type ('f' or 'h'), data offset (u64).
 */

export interface WeightTensor {
  dims: number[];
  layout: string;
  data: Float32Array;
}

const MAGIC = 0x41d7;

export class WeightsError extends Error {
  constructor(message: string) {
    super(`denoiser weights: ${message}`);
    this.name = 'WeightsError';
  }
}

export function parseTza(buffer: ArrayBuffer): Map<string, WeightTensor> {
  const view = new DataView(buffer);
  const need = (offset: number, bytes: number) => {
    if (offset + bytes > buffer.byteLength) throw new WeightsError(`truncated file (needs byte ${offset + bytes}, has ${buffer.byteLength})`);
  };
  need(0, 12);
  if (view.getUint16(0, true) !== MAGIC) throw new WeightsError('not a TZA file (bad magic number)');
  if (view.getUint8(2) !== 2) throw new WeightsError(`unsupported TZA version ${view.getUint8(2)} (expected 2)`);
  let offset = Number(view.getBigUint64(4, true));
  need(offset, 4);
  const count = view.getUint32(offset, true);
  offset += 4;
  const tensors = new Map<string, WeightTensor>();
  const text = new TextDecoder();
  for (let i = 0; i < count; i++) {
    need(offset, 2);
    const nameLength = view.getUint16(offset, true);
    need(offset + 2, nameLength + 1);
    const name = text.decode(new Uint8Array(buffer, offset + 2, nameLength));
    offset += 2 + nameLength;
    const ndims = view.getUint8(offset++);
    need(offset, ndims * 5 + 9);
    const dims: number[] = [];
    for (let d = 0; d < ndims; d++, offset += 4) dims.push(view.getUint32(offset, true));
    const layout = text.decode(new Uint8Array(buffer, offset, ndims));
    offset += ndims;
    const type = String.fromCharCode(view.getUint8(offset++));
    const dataOffset = Number(view.getBigUint64(offset, true));
    offset += 8;
    const size = dims.reduce((a, b) => a * b, 1);
    tensors.set(name, { dims, layout, data: readValues(view, dataOffset, size, type, name) });
  }
  return tensors;
}

function readValues(view: DataView, offset: number, size: number, type: string, name: string): Float32Array {
  const bytes = type === 'h' ? 2 : type === 'f' ? 4 : 0;
  if (bytes === 0) throw new WeightsError(`${name}: unknown data type "${type}"`);
  if (offset + size * bytes > view.byteLength) throw new WeightsError(`${name}: data runs past the end of the file`);
  const out = new Float32Array(size);
  for (let i = 0; i < size; i++) {
    out[i] = bytes === 4 ? view.getFloat32(offset + 4 * i, true) : halfToFloat(view.getUint16(offset + 2 * i, true));
  }
  return out;
}

/** IEEE 754 binary16 to number. */
export function halfToFloat(h: number): number {
  const sign = h & 0x8000 ? -1 : 1;
  const exponent = (h >> 10) & 0x1f;
  const fraction = h & 0x3ff;
  if (exponent === 0) return sign * fraction * 2 ** -24;
  if (exponent === 31) return fraction ? NaN : sign * Infinity;
  return sign * (1 + fraction / 1024) * 2 ** (exponent - 15);
}
