/**
 * Time to load a 2k environment map (also printed by `npm run bench`): decode (.hdr RLE; .exr half, none and
 * ZIP, and the studio map's own PIZ at 512x256) and build its sampling
 * distribution, in Node. The 2k map is test/fixtures/envmaps/studio.exr
 * upsampled (bilinear) to 2048 x 1024 and written here in each format.
 *
 *   npx tsx bench/envmap-load.ts [--runs 7]
 */
import { readFileSync } from 'node:fs';
import { deflateSync } from 'node:zlib';
import { DataUtils } from 'three';
import { decodeEnvironmentMap } from '../src/scene/envmap/decode';
import { buildEnvironmentDistribution } from '../src/scene/envmap/distribution';
import { lookupEnvironment } from '../src/scene/envmap/mapping';
import type { EnvironmentImage } from '../src/scene/types';
import { projectRoot } from './common';

const WIDTH = 2048;
const HEIGHT = 1024;

function upsample(image: EnvironmentImage, width: number, height: number): EnvironmentImage {
  const rgb = new Float32Array(width * height * 3);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) rgb.set(lookupEnvironment(image, (x + 0.5) / width, y / (height - 1)), (y * width + x) * 3);
  }
  return { width, height, rgb };
}

/** Radiance RGBE with new-style RLE scanlines (runs of 4+ equal bytes). */
function encodeHdr(image: EnvironmentImage): Uint8Array {
  const parts: number[] = [...Buffer.from(`#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y ${image.height} +X ${image.width}\n`, 'latin1')];
  const planes = Array.from({ length: 4 }, () => new Uint8Array(image.width));
  for (let y = 0; y < image.height; y++) {
    for (let x = 0; x < image.width; x++) {
      const i = (y * image.width + x) * 3;
      const v = Math.max(image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]);
      if (v < 1e-32) { planes.forEach((p) => (p[x] = 0)); continue; }
      const e = Math.ceil(Math.log2(v * (1 + 1e-9)));
      const scale = 2 ** (8 - e);
      [0, 1, 2].forEach((c) => (planes[c][x] = Math.min(255, Math.floor(image.rgb[i + c] * scale))));
      planes[3][x] = e + 128;
    }
    parts.push(2, 2, image.width >> 8, image.width & 255);
    for (const plane of planes) encodeRlePlane(plane, parts);
  }
  return new Uint8Array(parts);
}

function encodeRlePlane(plane: Uint8Array, out: number[]): void {
  let i = 0;
  while (i < plane.length) {
    let run = 1;
    while (i + run < plane.length && run < 127 && plane[i + run] === plane[i]) run++;
    if (run >= 4) { out.push(128 + run, plane[i]); i += run; continue; }
    const start = i;
    while (i < plane.length && i - start < 128 && !(i + 3 < plane.length && plane[i] === plane[i + 1] && plane[i] === plane[i + 2] && plane[i] === plane[i + 3])) i++;
    out.push(i - start, ...plane.subarray(start, i));
  }
}

/** OpenEXR scanline file, half RGB, NONE or ZIP (16 scanlines per chunk, OpenEXR's reorder + predictor + zlib). */
function encodeExr(image: EnvironmentImage, zip: boolean): Uint8Array {
  const { width, height } = image;
  const header: number[] = [0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0];
  const attribute = (name: string, type: string, value: number[]) => {
    header.push(...Buffer.from(`${name}\0${type}\0`, 'latin1'), ...int32(value.length), ...value);
  };
  const channels: number[] = [];
  for (const c of ['B', 'G', 'R']) channels.push(c.charCodeAt(0), 0, ...int32(1), 0, 0, 0, 0, ...int32(1), ...int32(1));
  channels.push(0);
  const box = [...int32(0), ...int32(0), ...int32(width - 1), ...int32(height - 1)];
  attribute('channels', 'chlist', channels);
  attribute('compression', 'compression', [zip ? 3 : 0]);
  attribute('dataWindow', 'box2i', box);
  attribute('displayWindow', 'box2i', box);
  attribute('lineOrder', 'lineOrder', [0]);
  attribute('pixelAspectRatio', 'float', float32(1));
  attribute('screenWindowCenter', 'v2f', [...float32(0), ...float32(0)]);
  attribute('screenWindowWidth', 'float', float32(1));
  header.push(0);
  const linesPerChunk = zip ? 16 : 1;
  const chunks: Uint8Array[] = [];
  for (let y0 = 0; y0 < height; y0 += linesPerChunk) {
    const lines = Math.min(linesPerChunk, height - y0);
    const raw = new Uint8Array(lines * width * 3 * 2);
    const view = new DataView(raw.buffer);
    for (let l = 0; l < lines; l++) {
      for (let c = 0; c < 3; c++) {
        for (let x = 0; x < width; x++) {
          view.setUint16(((l * 3 + c) * width + x) * 2, DataUtils.toHalfFloat(image.rgb[((y0 + l) * width + x) * 3 + (2 - c)]), true);
        }
      }
    }
    const data = zip ? zipChunk(raw) : raw;
    chunks.push(new Uint8Array([...int32(y0), ...int32(data.length)]), data);
  }
  const tableStart = header.length;
  const table = new DataView(new ArrayBuffer((chunks.length / 2) * 8));
  let offset = tableStart + table.byteLength;
  for (let i = 0; i < chunks.length; i += 2) {
    table.setBigUint64((i / 2) * 8, BigInt(offset), true);
    offset += chunks[i].length + chunks[i + 1].length;
  }
  return Buffer.concat([new Uint8Array(header), new Uint8Array(table.buffer), ...chunks]);
}

function zipChunk(raw: Uint8Array): Uint8Array {
  const reordered = new Uint8Array(raw.length);
  const half = Math.ceil(raw.length / 2);
  for (let i = 0; i < raw.length; i++) reordered[(i & 1) === 0 ? i >> 1 : half + (i >> 1)] = raw[i];
  for (let i = reordered.length - 1; i > 0; i--) reordered[i] = (reordered[i] - reordered[i - 1] + 128) & 255;
  return deflateSync(reordered);
}

function int32(v: number): number[] {
  return [v & 255, (v >> 8) & 255, (v >> 16) & 255, (v >>> 24) & 255];
}

function float32(v: number): number[] {
  return [...new Uint8Array(new Float32Array([v]).buffer)];
}

function median(values: number[]): number {
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.floor(sorted.length / 2)];
}

/** Median wall and CPU milliseconds of `runs` calls (CPU time: the machine may be shared). */
function time(runs: number, f: () => void): { wall: number; cpu: number } {
  f(); // warm-up (JIT)
  const wall: number[] = [];
  const cpu: number[] = [];
  for (let i = 0; i < runs; i++) {
    const start = performance.now();
    const startCpu = process.cpuUsage();
    f();
    const used = process.cpuUsage(startCpu);
    wall.push(performance.now() - start);
    cpu.push((used.user + used.system) / 1000);
  }
  return { wall: median(wall), cpu: median(cpu) };
}

export interface EnvmapLoadRow {
  map: string;
  fileMB: number;
  decodeMs: { wall: number; cpu: number };
  distributionMs: { wall: number; cpu: number };
}

/** Decode and distribution times of the studio map and of its 2k versions in three formats. */
export function measureEnvmapLoad(runs: number): EnvmapLoadRow[] {
  const studioBytes = new Uint8Array(readFileSync(new URL('test/fixtures/envmaps/studio.exr', projectRoot())));
  const big = upsample(decodeEnvironmentMap(studioBytes, 'studio.exr'), WIDTH, HEIGHT);
  const files: [string, Uint8Array][] = [
    ['studio.exr 512x256 half PIZ', studioBytes],
    [`${WIDTH}x${HEIGHT} .hdr RLE`, encodeHdr(big)],
    [`${WIDTH}x${HEIGHT} .exr half none`, encodeExr(big, false)],
    [`${WIDTH}x${HEIGHT} .exr half ZIP`, encodeExr(big, true)],
  ];
  return files.map(([map, bytes]) => {
    const fileName = map.includes('.hdr') ? 'map.hdr' : 'map.exr';
    let image = decodeEnvironmentMap(bytes, fileName);
    const decodeMs = time(runs, () => (image = decodeEnvironmentMap(bytes, fileName)));
    const distributionMs = time(runs, () => buildEnvironmentDistribution(image));
    return { map, fileMB: bytes.length / 1e6, decodeMs, distributionMs };
  });
}

export function formatEnvmapLoad(rows: EnvmapLoadRow[], runs: number): string {
  const f = (t: { wall: number; cpu: number }) => `${t.wall.toFixed(1)} / ${t.cpu.toFixed(1)}`;
  const cells = rows.map((r) => [r.map, `${r.fileMB.toFixed(2)} MB`, f(r.decodeMs), f(r.distributionMs)]);
  const header = ['map', 'file', 'decode ms (wall / CPU)', 'distribution ms (wall / CPU)'];
  const widths = header.map((h, i) => Math.max(h.length, ...cells.map((r) => r[i].length)));
  const line = (c: string[]) => `| ${c.map((x, i) => x.padEnd(widths[i])).join(' | ')} |`;
  return [
    `Environment map load, Node ${process.version}, median of ${runs} runs (the page does both in a Worker)`,
    line(header),
    `|${widths.map((w) => '-'.repeat(w + 2)).join('|')}|`,
    ...cells.map(line),
  ].join('\n');
}

// Run directly (not when bundled into the bench, whose import.meta.url is the bundle's).
if (/envmap-load\.[cm]?[jt]s$/.test(process.argv[1] ?? '')) {
  const runsIndex = process.argv.indexOf('--runs');
  const runs = runsIndex > 0 ? Number(process.argv[runsIndex + 1]) : 7;
  console.log(formatEnvmapLoad(measureEnvmapLoad(runs), runs));
}
