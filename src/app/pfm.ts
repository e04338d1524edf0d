/**
 * PFM encoding in the browser (no Node Buffer): an ASCII header, then
 * little-endian float32 RGB, rows from bottom to top (the PFM convention).
 */
export function encodePfm(width: number, height: number, rgbaTopDown: Float32Array): Uint8Array<ArrayBuffer> {
  const header = new TextEncoder().encode(`PF\n${width} ${height}\n-1.0\n`);
  const bytes = new Uint8Array(header.length + width * height * 12);
  bytes.set(header, 0);
  const view = new DataView(bytes.buffer, header.length);
  let offset = 0;
  for (let y = height - 1; y >= 0; y--) {
    for (let x = 0; x < width; x++) {
      const p = (y * width + x) * 4;
      for (let c = 0; c < 3; c++, offset += 4) view.setFloat32(offset, rgbaTopDown[p + c], true);
    }
  }
  return bytes;
}
