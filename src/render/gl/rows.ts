/** GL rows run bottom to top; the library's images run top to bottom. Returns a flipped copy. */
export function flipRows<T extends Float32Array | Uint8Array>(data: T, width: number, height: number, channels: number): T {
  const out = new (data.constructor as { new (n: number): T })(data.length);
  const row = width * channels;
  for (let y = 0; y < height; y++) out.set(data.subarray((height - 1 - y) * row, (height - y) * row), y * row);
  return out;
}
