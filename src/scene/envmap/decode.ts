/**
 * Decodes an environment map file (Radiance `.hdr` or OpenEXR `.exr`, told
 * apart by their signatures, the name only helping the error message) into
 * linear RGB float32, rows from the zenith down. Pure TypeScript: the page,
 * the CLI and the tests share it.
 */
import { AssetError } from '../assetError';
import type { EnvironmentImage } from '../types';
import { decodeExr } from './exr';
import { decodeRgbe } from './rgbe';

export { MAX_ENVIRONMENT_WIDTH, MAX_ENVIRONMENT_HEIGHT } from './limits';

const EXR_SIGNATURE = [0x76, 0x2f, 0x31, 0x01];
const RGBE_SIGNATURE = [0x23, 0x3f]; // "#?"

function startsWith(bytes: Uint8Array, signature: number[]): boolean {
  return signature.every((b, i) => bytes[i] === b);
}

/**
 * Throws AssetError (message without the scene path; the caller prefixes
 * `environment.map: `) for an empty, truncated, corrupt, unsupported or
 * oversized file. Non-finite texels (NaN, overflowed half floats) are set to
 * 0: one bad texel must not turn the whole image into NaN. Negative texels
 * are kept as they are: the format defines the map as Mitsuba's envmap,
 * which looks them up unchanged (lossy EXR codecs such as DWAB ring below
 * zero next to bright lights; zeroing them brightens those neighbourhoods by
 * up to ~25% against Mitsuba). Importance sampling clamps luminance at 0.
 */
export function decodeEnvironmentMap(bytes: Uint8Array, fileName: string): EnvironmentImage {
  if (bytes.length === 0) throw new AssetError('the file is empty');
  const extension = /\.([^./\\]+)$/.exec(fileName)?.[1]?.toLowerCase() ?? '';
  let image: EnvironmentImage;
  if (startsWith(bytes, EXR_SIGNATURE)) image = decodeExr(bytes);
  else if (startsWith(bytes, RGBE_SIGNATURE)) image = decodeRgbe(bytes);
  else if (extension === 'exr') throw new AssetError('not an OpenEXR file (bad magic number)');
  else if (extension === 'hdr') throw new AssetError('not a Radiance .hdr file (it must start with "#?RADIANCE" or "#?RGBE")');
  else throw new AssetError(`"${fileName}" is neither an OpenEXR (.exr) nor a Radiance (.hdr) image`);
  zeroInvalidTexels(image.rgb);
  return image;
}

/** Replaces NaN and infinities by 0 (see above). */
export function zeroInvalidTexels(rgb: Float32Array): number {
  let replaced = 0;
  for (let i = 0; i < rgb.length; i++) {
    const v = rgb[i];
    if (!Number.isFinite(v)) {
      rgb[i] = 0;
      replaced++;
    }
  }
  return replaced;
}
