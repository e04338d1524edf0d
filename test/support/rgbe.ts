/** Writes a flat (not run-length-encoded) Radiance .hdr file, for tests that need a map of known texels. */
export function encodeFlatHdr(width: number, height: number, texel: (x: number, y: number) => [number, number, number]): Uint8Array {
  const header = new TextEncoder().encode(`#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y ${height} +X ${width}\n`);
  const out = new Uint8Array(header.length + width * height * 4);
  out.set(header);
  let o = header.length;
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++, o += 4) {
      const rgb = texel(x, y);
      const v = Math.max(...rgb);
      if (v < 1e-32) continue; // (0, 0, 0, 0)
      const e = Math.ceil(Math.log2(v * (1 + 1e-9))); // v < 2^e
      const scale = 2 ** (8 - e);
      for (let c = 0; c < 3; c++) out[o + c] = Math.min(255, Math.floor(rgb[c] * scale));
      out[o + 3] = e + 128;
    }
  }
  return out;
}
