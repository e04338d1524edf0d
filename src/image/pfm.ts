/**
 * Portable Float Map (PFM) encoding and decoding, for the page, the CLI and
 * the tests alike (plain typed arrays, no Node Buffer).
 *
 * PFM stores rows bottom to top; a negative scale means little-endian floats.
 * Everywhere else in this project images are rows top to bottom, so both
 * functions flip rows at the boundary and callers never see the PFM order.
 */

export interface PfmImage {
  width: number;
  height: number;
  /** RGB float32, rows top to bottom, width * height * 3 values. */
  rgb: Float32Array;
  /** The absolute value of the header's scale field (usually 1; readers ignore it). */
  scale: number;
}

/**
 * Encodes RGBA float32 pixels (rows top to bottom, alpha dropped) as a
 * colour PFM: `PF\n<w> <h>\n-1.0\n`, then little-endian float32 RGB rows
 * from the bottom row up.
 */
export function encodePfm(width: number, height: number, rgba: Float32Array): Uint8Array<ArrayBuffer> {
  checkSize(width, height);
  if (rgba.length !== width * height * 4) {
    throw new RangeError(`encodePfm: expected ${width * height * 4} RGBA floats, got ${rgba.length}`);
  }
  const header = new TextEncoder().encode(`PF\n${width} ${height}\n-1.0\n`);
  const bytes = new Uint8Array(header.length + width * height * 12);
  bytes.set(header, 0);
  const body = new DataView(bytes.buffer, header.length);
  for (let fileRow = 0; fileRow < height; fileRow++) {
    const imageRow = height - 1 - fileRow;
    for (let x = 0; x < width; x++) {
      const src = (imageRow * width + x) * 4;
      const dst = (fileRow * width + x) * 12;
      for (let c = 0; c < 3; c++) body.setFloat32(dst + c * 4, rgba[src + c], true);
    }
  }
  return bytes;
}

/**
 * Encodes float32 values of 1 or 3 channels (rows top to bottom) as a PFM:
 * greyscale `Pf` for one channel, colour `PF` for three, little-endian,
 * rows from the bottom up. The Mitsuba exporter's baked textures: Mitsuba's
 * `bitmap` reads a `Pf` file as a one-channel texture.
 */
export function encodePfmChannels(width: number, height: number, channels: 1 | 3, values: Float32Array): Uint8Array<ArrayBuffer> {
  checkSize(width, height);
  if (values.length !== width * height * channels) {
    throw new RangeError(`encodePfmChannels: expected ${width * height * channels} floats, got ${values.length}`);
  }
  const header = new TextEncoder().encode(`${channels === 3 ? 'PF' : 'Pf'}\n${width} ${height}\n-1.0\n`);
  const rowFloats = width * channels;
  const bytes = new Uint8Array(header.length + width * height * channels * 4);
  bytes.set(header, 0);
  const body = new DataView(bytes.buffer, header.length);
  for (let fileRow = 0; fileRow < height; fileRow++) {
    const src = (height - 1 - fileRow) * rowFloats;
    for (let i = 0; i < rowFloats; i++) body.setFloat32((fileRow * rowFloats + i) * 4, values[src + i], true);
  }
  return bytes;
}

/**
 * Decodes a PFM (colour `PF` or greyscale `Pf`, either byte order) into RGB
 * float32 rows top to bottom. Greyscale values are copied to all three channels.
 */
export function decodePfm(data: Uint8Array): PfmImage {
  const bytes = data;
  const view = new DataView(data.buffer, data.byteOffset, data.byteLength);
  const { tokens, bodyOffset } = readHeader(bytes);
  const [magic, w, h, s] = tokens;
  if (magic !== 'PF' && magic !== 'Pf') throw new Error(`not a PFM file (magic ${JSON.stringify(magic)})`);
  const width = parseDimension(w, 'width');
  const height = parseDimension(h, 'height');
  const scaleField = Number(s);
  if (!Number.isFinite(scaleField) || scaleField === 0) throw new Error(`PFM: bad scale ${JSON.stringify(s)}`);
  const channels = magic === 'PF' ? 3 : 1;
  const expected = width * height * channels * 4;
  if (bytes.length - bodyOffset < expected) {
    throw new Error(`PFM: truncated, expected ${expected} bytes of pixels, got ${bytes.length - bodyOffset}`);
  }
  const littleEndian = scaleField < 0;
  const rgb = new Float32Array(width * height * 3);
  for (let fileRow = 0; fileRow < height; fileRow++) {
    const imageRow = height - 1 - fileRow;
    for (let x = 0; x < width; x++) {
      const src = bodyOffset + (fileRow * width + x) * channels * 4;
      const dst = (imageRow * width + x) * 3;
      for (let c = 0; c < 3; c++) {
        const at = src + (channels === 3 ? c * 4 : 0);
        rgb[dst + c] = view.getFloat32(at, littleEndian);
      }
    }
  }
  return { width, height, rgb, scale: Math.abs(scaleField) };
}

/** Reads the four whitespace-separated header tokens; one whitespace byte ends the header. */
function readHeader(bytes: Uint8Array): { tokens: string[]; bodyOffset: number } {
  const tokens: string[] = [];
  let i = 0;
  const limit = Math.min(bytes.length, 256);
  while (tokens.length < 4 && i < limit) {
    while (i < limit && isSpace(bytes[i])) i++;
    const start = i;
    while (i < limit && !isSpace(bytes[i])) i++;
    if (i > start) tokens.push(String.fromCharCode(...bytes.subarray(start, i)));
  }
  if (tokens.length < 4 || i >= bytes.length || !isSpace(bytes[i])) throw new Error('PFM: incomplete header');
  return { tokens, bodyOffset: i + 1 };
}

function isSpace(byte: number): boolean {
  return byte === 0x20 || byte === 0x0a || byte === 0x0d || byte === 0x09;
}

function parseDimension(token: string, name: string): number {
  const value = Number(token);
  if (!/^\d+$/.test(token) || value < 1) throw new Error(`PFM: bad ${name} ${JSON.stringify(token)}`);
  return value;
}

function checkSize(width: number, height: number): void {
  if (!Number.isInteger(width) || !Number.isInteger(height) || width < 1 || height < 1) {
    throw new RangeError(`bad image size ${width}x${height}`);
  }
}
