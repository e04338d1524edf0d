/**
 * The length of lz-string's decompressFromEncodedURIComponent(payload),
 * computed from the bit stream without building the text. A share link is
 * untrusted and LZ output grows with the square of its input (a 41 KB link
 * can expand to 200 million characters), so the size limit must be checked
 * before decompressing. Mirrors lz-string 1.5's _decompress loop, tracking
 * only the dictionary entries' lengths.
 */
const KEY = 'ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+-$';

/**
 * Returns the decompressed length in UTF-16 units, Infinity once it exceeds
 * `limit`, 0 for a truncated stream (lz-string returns "") and -1 for a
 * malformed one (lz-string returns null).
 */
export function lzDecompressedLength(payload: string, limit: number): number {
  const input = payload.replace(/ /g, '+');
  const valueAt = (i: number) => Math.max(0, KEY.indexOf(input.charAt(i)));
  let index = 1;
  let value = valueAt(0);
  let position = 32;
  const read = (n: number): number => {
    let bits = 0;
    for (let p = 0; p < n; p++) {
      const bit = value & position;
      position >>= 1;
      if (position === 0) {
        position = 32;
        value = valueAt(index++);
      }
      if (bit) bits |= 1 << p;
    }
    return bits;
  };
  const first = read(2);
  if (first === 2) return 0;
  read(first === 0 ? 8 : 16);
  const lengths = [0, 0, 0, 1]; // entry lengths; codes 0-2 are control codes
  let dictSize = 4;
  let numBits = 3;
  let enlargeIn = 4;
  let previous = 1;
  let total = 1;
  for (;;) {
    if (index > input.length) return 0;
    let code = read(numBits);
    if (code === 2) return total;
    if (code < 2) {
      read(code === 0 ? 8 : 16);
      lengths[dictSize++] = 1;
      code = dictSize - 1;
      enlargeIn--;
    }
    if (enlargeIn === 0) {
      enlargeIn = 2 ** numBits;
      numBits++;
    }
    let entry: number;
    if (code < dictSize && lengths[code] > 0) entry = lengths[code];
    else if (code === dictSize) entry = previous + 1;
    else return -1;
    total += entry;
    if (total > limit) return Infinity;
    lengths[dictSize++] = previous + 1;
    enlargeIn--;
    previous = entry;
    if (enlargeIn === 0) {
      enlargeIn = 2 ** numBits;
      numBits++;
    }
  }
}
