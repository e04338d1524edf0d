/**
 * A JPEG's EXIF orientation, and undoing it. Browsers apply it in
 * createImageBitmap whatever the options (Chromium 156 turns a JPEG of
 * orientation 6 into a portrait bitmap even with imageOrientation 'none'),
 * while Mitsuba reads the texels as stored (its libjpeg loader ignores EXIF:
 * mi.Bitmap of such a file keeps the stored size). The texture is Mitsuba's,
 * so the decoder turns the browser's bitmap back to the stored orientation.
 */

const EXIF_HEADER = [0x45, 0x78, 0x69, 0x66, 0, 0]; // "Exif\0\0"
const ORIENTATION_TAG = 0x0112;

/** The EXIF orientation (1..8) of a JPEG's first APP1 Exif segment; 1 where there is none or it cannot be read. */
export function jpegExifOrientation(bytes: Uint8Array): number {
  let pos = 2;
  while (pos + 4 <= bytes.length && bytes[pos] === 0xff) {
    const marker = bytes[pos + 1];
    if (marker === 0xda || marker === 0xd9) break; // image data: no metadata after it counts
    if (marker === 0xff) {
      pos++;
      continue;
    }
    const length = (bytes[pos + 2] << 8) | bytes[pos + 3];
    if (length < 2) break;
    if (marker === 0xe1 && EXIF_HEADER.every((b, i) => bytes[pos + 4 + i] === b)) {
      return tiffOrientation(bytes.subarray(pos + 10, Math.min(bytes.length, pos + 2 + length)));
    }
    pos += 2 + length;
  }
  return 1;
}

/** Orientation from IFD0 of a TIFF structure (EXIF's container). */
function tiffOrientation(tiff: Uint8Array): number {
  if (tiff.length < 8) return 1;
  const little = tiff[0] === 0x49 && tiff[1] === 0x49;
  if (!little && !(tiff[0] === 0x4d && tiff[1] === 0x4d)) return 1;
  const view = new DataView(tiff.buffer, tiff.byteOffset, tiff.byteLength);
  const ifd = view.getUint32(4, little);
  if (ifd + 2 > tiff.length) return 1;
  const entries = view.getUint16(ifd, little);
  for (let i = 0; i < entries; i++) {
    const entry = ifd + 2 + i * 12;
    if (entry + 12 > tiff.length) return 1;
    if (view.getUint16(entry, little) !== ORIENTATION_TAG) continue;
    const value = view.getUint16(entry + 8, little); // SHORT, count 1: the value sits in the entry
    return value >= 1 && value <= 8 ? value : 1;
  }
  return 1;
}

/** Whether an orientation swaps width and height (5..8 turn the image a quarter). */
export function swapsSides(orientation: number): boolean {
  return orientation >= 5;
}

/**
 * The stored image (width x height) from the displayed one that the
 * orientation made of it (RGBA8, height x width for orientations 5..8).
 */
export function undoOrientation(displayed: Uint8Array, width: number, height: number, orientation: number): Uint8Array {
  if (orientation === 1) return displayed;
  const displayedWidth = swapsSides(orientation) ? height : width;
  const out = new Uint8Array(width * height * 4);
  const aligned = displayed.byteOffset % 4 === 0 ? displayed : displayed.slice();
  const view32 = new Uint32Array(aligned.buffer, aligned.byteOffset, width * height);
  const out32 = new Uint32Array(out.buffer);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      // Where the stored texel (x, y) shows (EXIF 2.32, the Orientation tag's table).
      let dx: number;
      let dy: number;
      switch (orientation) {
        case 2: dx = width - 1 - x; dy = y; break;
        case 3: dx = width - 1 - x; dy = height - 1 - y; break;
        case 4: dx = x; dy = height - 1 - y; break;
        case 5: dx = y; dy = x; break;
        case 6: dx = height - 1 - y; dy = x; break;
        case 7: dx = height - 1 - y; dy = width - 1 - x; break;
        default: dx = y; dy = width - 1 - x; break; // 8
      }
      out32[y * width + x] = view32[dy * displayedWidth + dx];
    }
  }
  return out;
}
