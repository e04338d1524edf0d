/**
 * File and link I/O of the page. Everything that comes in (files, links) is
 * untrusted: it is size-limited, parsed with the one scene parser, and only
 * ever shown as text.
 */
import { lzDecompressedLength } from './lzLength';
import { compressToEncodedURIComponent, decompressFromEncodedURIComponent } from 'lz-string';
import { MAX_SCENE_BYTES } from '../scene/limits';
import { safeParseSceneText, type SafeParseResult } from '../scene/schema';
import { serializeScene } from '../scene/serialize';
import type { Scene } from '../scene/types';

export const SHARE_PREFIX = '#scene=';

function failure(message: string): SafeParseResult {
  return { ok: false, issues: [{ path: '', message }] };
}

export async function readSceneFile(file: File): Promise<SafeParseResult> {
  if (file.size > MAX_SCENE_BYTES) return failure(`the file is ${file.size} bytes; a scene may be at most ${MAX_SCENE_BYTES}`);
  let text: string;
  try {
    text = await file.text();
  } catch (error) {
    return failure(`could not read the file (${(error as Error).message})`);
  }
  return safeParseSceneText(text);
}

/** The URL hash that carries `scene`: "#scene=" + lz-string of the serialized JSON. */
export function shareHash(scene: Scene): string {
  return SHARE_PREFIX + compressToEncodedURIComponent(JSON.stringify(serializeScene(scene)));
}

/** The scene in a share hash; null when the hash carries none. */
export function sceneFromHash(hash: string): SafeParseResult | null {
  if (!hash.startsWith(SHARE_PREFIX)) return null;
  const payload = hash.slice(SHARE_PREFIX.length);
  // Compression never makes a scene longer than its text, so a longer payload is not ours.
  if (payload.length > MAX_SCENE_BYTES) return failure('the link is too long to be a scene');
  // Checked before decompressing: LZ output can be quadratically larger than its input.
  // (UTF-16 units never outnumber UTF-8 bytes, so this limit is never too strict.)
  if (lzDecompressedLength(payload, MAX_SCENE_BYTES) === Infinity) return failure('the link is too large to be a scene');
  let text: string | null = null;
  try {
    text = decompressFromEncodedURIComponent(payload);
  } catch {
    text = null;
  }
  if (!text) return failure('the link is damaged: its scene could not be decompressed');
  return safeParseSceneText(text);
}

export function downloadBlob(blob: Blob, filename: string): void {
  const url = URL.createObjectURL(blob);
  const link = document.createElement('a');
  link.href = url;
  link.download = filename;
  link.style.display = 'none';
  document.body.append(link);
  link.click();
  link.remove();
  setTimeout(() => URL.revokeObjectURL(url), 30_000);
}

/** RGBA8 rows (top to bottom) -> PNG blob, through a 2D canvas. */
export function rgba8ToPngBlob(width: number, height: number, pixels: Uint8Array): Promise<Blob> {
  const canvas = document.createElement('canvas');
  canvas.width = width;
  canvas.height = height;
  const context = canvas.getContext('2d');
  if (!context) return Promise.reject(new Error('no 2D canvas to encode the PNG'));
  context.putImageData(new ImageData(new Uint8ClampedArray(pixels), width, height), 0, 0);
  return new Promise((resolve, reject) =>
    canvas.toBlob((blob) => (blob ? resolve(blob) : reject(new Error('PNG encoding failed'))), 'image/png'),
  );
}
