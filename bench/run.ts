/**
 * The convergence benchmark: every fixture scene rendered headless through
 * the CLI's code path (openRenderSession), its relMSE against the Mitsuba
 * reference after equal wall times, its path rate, and the time to reach a
 * target relMSE; optionally Mitsuba 3 on the same scene for the same times.
 *
 * Timing: the clock starts after the scene is loaded and the shader compiled
 * (a throw-away load warms Chromium's shader cache; the compile time is
 * reported as `startupSeconds`) and pauses while images are read back and
 * scored. Mitsuba's times likewise exclude scene loading (render.py).
 */
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { decodePfm } from '../src/image/pfm';
import { relativeMse, type LinearImage } from '../src/node/imageMetrics';
import { openRenderSession, type LoadOptions, type RenderSession } from '../src/node/session';
import type { SamplerKind } from '../src/render/sampling';
import { bakedTextureFile, exportMitsuba, meshPlyFile } from '../src/scene/mitsuba';
import { resolveFileMaterials } from '../src/scene/fileMaterials';
import type { SceneAssets } from '../src/scene/assets';
import { parseSceneText } from '../src/scene/schema';
import { readSceneFiles } from '../src/node/sceneFiles';
import { fileURLToPath } from 'node:url';
import type { Scene } from '../src/scene/types';
import { gitRevision, machineInfo, projectRoot, type MachineInfo } from './common';

/** What a row of ours runs: a sampler, or 'adaptive' (the Kronecker sampler with PathTracerOptions.adaptive). */
export type BenchSampler = SamplerKind | 'adaptive';

export const FIXTURES = new URL('test/fixtures/', projectRoot());

export interface BenchOptions {
  /** Scene names in test/fixtures/scenes (default: all that have a reference). */
  scenes?: string[];
  /** Equal-time checkpoints in seconds, ascending (default 2, 5, 10). */
  times?: number[];
  /** Render size as a multiple of the reference's (integer; default 1). */
  scale?: number;
  /** relMSE whose time to reach is reported (default 0.02). */
  target?: number;
  /** Run Mitsuba 3 for comparison: 'auto' = when `import mitsuba` works (default). */
  mitsuba?: boolean | 'auto';
  seed?: number;
  /** Samplers to run, each a row per scene, interleaved (default ['kronecker']; A/B: kronecker,independent). */
  samplers?: BenchSampler[];
  log?: (line: string) => void;
}

export interface Checkpoint {
  seconds: number;
  spp: number;
  relMse: number;
}

export interface RendererRun {
  checkpoints: Checkpoint[];
  megaPathsPerSecond: number;
  /** Seconds to reach the target relMSE; extrapolated (1/t) when not reached. */
  timeToTarget: number;
  timeToTargetExtrapolated: boolean;
}

export interface SceneRow {
  scene: string;
  sampler: BenchSampler;
  width: number;
  height: number;
  maxBounces: number;
  startupSeconds: number;
  /** GPU bytes of the scene's texture images (the atlas), 0 without textures. */
  textureBytes: number;
  ours: RendererRun;
  mitsuba?: RendererRun & { cpuSeconds: number[] };
  /** Our relMSE / Mitsuba's at each checkpoint. */
  ratio?: number[];
}

export interface BenchResult {
  kind: 'convergence';
  date: string;
  revision: string;
  machine: MachineInfo;
  renderer: string;
  mitsubaVersion?: string;
  options: Required<Omit<BenchOptions, 'log' | 'mitsuba'>> & { mitsuba: boolean };
  rows: SceneRow[];
}

export function fixtureSceneNames(): string[] {
  return readdirSync(new URL('scenes/', FIXTURES))
    .filter((f) => f.endsWith('.json') && existsSync(new URL(`references/${f.replace(/\.json$/, '.pfm')}`, FIXTURES)))
    .map((f) => f.replace(/\.json$/, ''))
    .sort();
}



function loadReference(name: string): LinearImage {
  const pfm = decodePfm(readFileSync(new URL(`references/${name}.pfm`, FIXTURES)));
  return { width: pfm.width, height: pfm.height, channels: 3, data: pfm.rgb };
}

/** Box-filters an image down by an integer factor: the mean over each factor x factor square is that pixel's box-filtered value. */
export function downsample(image: LinearImage, factor: number): LinearImage {
  if (factor === 1) return image;
  const width = image.width / factor;
  const height = image.height / factor;
  const data = new Float32Array(width * height * 3);
  const w = 1 / (factor * factor);
  for (let y = 0; y < image.height; y++) {
    for (let x = 0; x < image.width; x++) {
      const src = (y * image.width + x) * image.channels;
      const dst = (Math.floor(y / factor) * width + Math.floor(x / factor)) * 3;
      for (let c = 0; c < 3; c++) data[dst + c] += image.data[src + c] * w;
    }
  }
  return { width, height, channels: 3, data };
}

export function mitsubaAvailable(): string | undefined {
  try {
    return execFileSync('python3', ['-c', 'import mitsuba; print(mitsuba.__version__)'], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] }).trim();
  } catch {
    return undefined;
  }
}

function finishRun(checkpoints: Checkpoint[], pixels: number, target: number, reached?: number): RendererRun {
  const last = checkpoints[checkpoints.length - 1];
  return {
    checkpoints,
    megaPathsPerSecond: (last.spp * pixels) / last.seconds / 1e6,
    timeToTarget: reached ?? (last.seconds * last.relMse) / target,
    timeToTargetExtrapolated: reached === undefined,
  };
}

export async function benchOurs(
  session: RenderSession,
  scene: Scene,
  size: { width: number; height: number },
  score: (image: LinearImage) => number,
  times: number[],
  target: number,
  seed: number,
  sampler: BenchSampler,
  files: Record<string, Uint8Array>,
): Promise<{ run: RendererRun; startupSeconds: number; textureBytes: number }> {
  // Load and a first draw: shader compile, link and SwiftShader's JIT (timed
  // as startup), then a fresh accumulation on the same context.
  const t0 = performance.now();
  const adaptive = sampler === 'adaptive';
  const options: LoadOptions = { ...size, seed, sampler: adaptive ? 'kronecker' : sampler, adaptive };
  const loaded = (await session.load(scene, options, files)) as { textureBytes?: number } | undefined;
  await session.render(1);
  const startupSeconds = (performance.now() - t0) / 1000;
  await session.reset();

  const pixels = size.width * size.height;
  const checkpoints: Checkpoint[] = [];
  let reached: number | undefined;
  let spp = 0;
  let elapsed = 0;
  let rate = 0;
  // Chunks grow to about a second: fewer, fuller draws (SwiftShader's cost
  // per draw and per synchronisation is large), never past a checkpoint.
  let slice = 0.25;
  for (const checkpoint of times) {
    while (elapsed < checkpoint) {
      // The first draw measures the rate; then chunks of `slice` seconds, never past the checkpoint.
      const left = checkpoint - elapsed;
      const chunk = rate === 0 ? 1 : Math.max(1, Math.round(rate * Math.min(slice, left)));
      if (rate > 0 && chunk > rate * left * 1.5 && elapsed > 0) break; // the next sample would overshoot by far
      const start = performance.now();
      spp = await session.render(chunk);
      elapsed += (performance.now() - start) / 1000;
      rate = spp / elapsed;
      slice = Math.min(1, slice * 1.5);
      if (reached === undefined) {
        const relMse = score(await readImage(session, size));
        if (relMse <= target) reached = elapsed;
      }
    }
    checkpoints.push({ seconds: elapsed, spp, relMse: score(await readImage(session, size)) });
  }
  return { run: finishRun(checkpoints, pixels, target, reached), startupSeconds, textureBytes: loaded?.textureBytes ?? 0 };
}

async function readImage(session: RenderSession, size: { width: number; height: number }): Promise<LinearImage> {
  return { ...size, channels: 4, data: await session.readLinear() };
}

function benchMitsuba(
  sceneModel: Scene,
  size: { width: number; height: number },
  score: (image: LinearImage) => number,
  times: number[],
  target: number,
  seed: number,
  dir: string,
  sceneFile: string,
  allAssets: SceneAssets,
): RendererRun & { cpuSeconds: number[] } {
  // Meshes wearing their files' materials are exported one mesh per material.
  const { scene, assets } = resolveFileMaterials(sceneModel, allAssets);
  const xml = path.join(dir, 'scene.xml');
  const environmentMapPath = (map: string) => path.resolve(path.dirname(sceneFile), map);
  const meshPath = (i: number) => path.join(dir, `mesh${i}.ply`);
  const meshData = (i: number) => assets.meshes.get(scene.meshes[i].file)!;
  scene.meshes.forEach((mesh, i) => writeFileSync(meshPath(i), meshPlyFile(mesh, meshData(i))));
  const meshSmooth = (i: number) => meshData(i).normals !== null;
  const texturePath = (name: string) => path.join(dir, name);
  const exported = exportMitsuba(scene, { ...size, seed, environmentMapPath, meshPath, meshSmooth, images: assets.images, texturePath });
  for (const texture of exported.textures) writeFileSync(texturePath(texture.name), bakedTextureFile(texture));
  writeFileSync(xml, exported.xml);
  const script = new URL('bench/mitsuba/render.py', projectRoot()).pathname;
  const checkpoints: Checkpoint[] = [];
  const cpuSeconds: number[] = [];
  for (const t of times) {
    const out = path.join(dir, `mitsuba-${t}.pfm`);
    const stdout = execFileSync('python3', [script, xml, '--out', out, '--time', String(t), '--seed', String(seed)], {
      encoding: 'utf8',
      stdio: ['ignore', 'pipe', 'inherit'],
      maxBuffer: 64 * 1024 * 1024,
    });
    // The last line is the JSON summary; Mitsuba's own warnings (coloured) may share its start.
    const last = stdout.trim().split('\n').pop()!;
    const info = JSON.parse(last.slice(last.indexOf('{'))) as { spp: number; seconds: number; cpu_seconds: number };
    const pfm = decodePfm(readFileSync(out));
    checkpoints.push({ seconds: info.seconds, spp: info.spp, relMse: score({ ...size, channels: 3, data: pfm.rgb }) });
    cpuSeconds.push(info.cpu_seconds);
  }
  return { ...finishRun(checkpoints, size.width * size.height, target), cpuSeconds };
}

export async function runBench(options: BenchOptions = {}): Promise<BenchResult> {
  const scenes = options.scenes ?? fixtureSceneNames();
  const times = options.times ?? [2, 5, 10];
  const scale = options.scale ?? 1;
  const target = options.target ?? 0.02;
  const seed = options.seed ?? 1;
  const samplers = options.samplers ?? ['kronecker'];
  const log = options.log ?? (() => {});
  const mitsubaVersion = options.mitsuba === false ? undefined : mitsubaAvailable();
  if (options.mitsuba === true && !mitsubaVersion) throw new Error('Mitsuba 3 requested but "python3 -c \'import mitsuba\'" fails');
  const dir = mkdtempSync(path.join(os.tmpdir(), 'pathtrace-bench-'));
  const session = await openRenderSession();
  const rows: SceneRow[] = [];
  let renderer = '';
  let machine: MachineInfo;
  try {
    machine = await machineInfo(session);
    for (const name of scenes) {
      const sceneFile = fileURLToPath(new URL(`scenes/${name}.json`, FIXTURES));
      const scene = parseSceneText(readFileSync(sceneFile, 'utf8'));
      const { files, assets } = await readSceneFiles(scene, sceneFile);
      const reference = loadReference(name);
      const size = { width: reference.width * scale, height: reference.height * scale };
      const score = (image: LinearImage) => relativeMse(downsample(image, scale), reference);
      renderer = (await session.probe()).renderer;
      const sceneRows: SceneRow[] = [];
      for (const sampler of samplers) {
        log(`${name}: ours (${sampler})...`);
        const { run, startupSeconds, textureBytes } = await benchOurs(session, scene, size, score, times, target, seed, sampler, files);
        sceneRows.push({ scene: name, sampler, ...size, maxBounces: scene.render.maxBounces, startupSeconds, textureBytes, ours: run });
      }
      if (mitsubaVersion) {
        log(`${name}: Mitsuba...`);
        const mitsuba = benchMitsuba(scene, size, score, times, target, seed, dir, sceneFile, assets);
        for (const row of sceneRows) {
          row.mitsuba = mitsuba;
          row.ratio = row.ours.checkpoints.map((c, i) => c.relMse / mitsuba.checkpoints[i].relMse);
        }
      }
      for (const row of sceneRows) log(formatRow(row));
      rows.push(...sceneRows);
    }
  } finally {
    await session.close();
    rmSync(dir, { recursive: true, force: true });
  }
  return {
    kind: 'convergence',
    date: new Date().toISOString(),
    revision: gitRevision(),
    machine,
    renderer,
    mitsubaVersion,
    options: { scenes, times, scale, target, seed, samplers, mitsuba: !!mitsubaVersion },
    rows,
  };

}

const fmt = (v: number, digits = 3) => (Number.isFinite(v) ? v.toPrecision(digits) : String(v));

export function formatRow(row: SceneRow): string {
  const ours = row.ours.checkpoints.map((c) => `${fmt(c.relMse)}@${c.spp}`).join(' ');
  let line = `${row.scene} (${row.sampler}): ${row.width}x${row.height} b${row.maxBounces} ${fmt(row.ours.megaPathsPerSecond)} Mpath/s ${ours}`;
  if (row.ratio) line += ` ratio ${row.ratio.map((r) => fmt(r, 2)).join(' ')}`;
  return line;
}

/** The table, one row per scene. */
export function formatTable(result: BenchResult): string {
  const times = result.options.times;
  const header = ['scene', 'sampler', 'size', 'bounces', 'tex MB', 'Mpath/s', ...times.map((t) => `spp@${t}s`), ...times.map((t) => `relMSE@${t}s`), `t(${result.options.target})`];
  if (result.mitsubaVersion) {
    header.push('Mi Mpath/s', ...times.map((t) => `Mi relMSE@${t}s`), `Mi t(${result.options.target})`, ...times.map((t) => `ours/Mi@${t}s`));
  }
  const time = (r: RendererRun) => `${r.timeToTargetExtrapolated ? '~' : ''}${r.timeToTarget.toFixed(2)}s`;
  const lines = result.rows.map((row) => {
    const cells = [
      row.scene,
      row.sampler,
      `${row.width}x${row.height}`,
      String(row.maxBounces),
      ((row.textureBytes ?? 0) / 2 ** 20).toFixed(1),
      fmt(row.ours.megaPathsPerSecond),
      ...row.ours.checkpoints.map((c) => String(c.spp)),
      ...row.ours.checkpoints.map((c) => c.relMse.toExponential(2)),
      time(row.ours),
    ];
    if (row.mitsuba && row.ratio) {
      cells.push(
        fmt(row.mitsuba.megaPathsPerSecond),
        ...row.mitsuba.checkpoints.map((c) => c.relMse.toExponential(2)),
        time(row.mitsuba),
        ...row.ratio.map((r) => r.toFixed(2)),
      );
    }
    return cells;
  });
  const widths = header.map((h, i) => Math.max(h.length, ...lines.map((l) => (l[i] ?? '').length)));
  const render = (cells: string[]) => cells.map((c, i) => c.padStart(widths[i])).join('  ');
  return [render(header), render(widths.map((w) => '-'.repeat(w))), ...lines.map(render)].join('\n');
}
