/**
 * Albedo and normal guides for the denoiser benchmark and fixtures, from
 * Mitsuba 3 (bench/denoise/guides.py) on the project's own export of the
 * scene, cached under bench/scratch/denoise/ (the tracer's own AOVs replace
 * them once PathTracer.readAovs() exists).
 */
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { decodePfm } from '../../src/image/pfm';
import { toMitsubaXml } from '../../src/scene/mitsuba';
import type { Scene } from '../../src/scene/types';

export interface Guides {
  albedo: Float32Array;
  normal: Float32Array;
}

/** A PFM file as RGBA float32, rows top to bottom (alpha 1). */
export function readPfmRgba(path: string): { width: number; height: number; data: Float32Array } {
  const image = decodePfm(readFileSync(path));
  const data = new Float32Array(image.width * image.height * 4);
  for (let p = 0; p < image.width * image.height; p++) {
    data.set(image.rgb.subarray(p * 3, p * 3 + 3), p * 4);
    data[p * 4 + 3] = 1;
  }
  return { width: image.width, height: image.height, data };
}

export function mitsubaGuides(root: URL, name: string, scene: Scene, width: number, height: number, spp = 32): Guides {
  const dir = fileURLToPath(new URL('bench/scratch/denoise/', root));
  mkdirSync(dir, { recursive: true });
  const base = `${dir}${name}-${width}x${height}-${spp}`;
  if (!existsSync(`${base}-normal.pfm`)) {
    writeFileSync(`${base}.xml`, toMitsubaXml(scene, { width, height, spp }));
    const script = fileURLToPath(new URL('bench/denoise/guides.py', root));
    execFileSync('python3', [script, `${base}.xml`, '--albedo', `${base}-albedo.pfm`, '--normal', `${base}-normal.pfm`, '--spp', String(spp)], {
      stdio: ['ignore', 'ignore', 'inherit'],
    });
  }
  return { albedo: readPfmRgba(`${base}-albedo.pfm`).data, normal: readPfmRgba(`${base}-normal.pfm`).data };
}
