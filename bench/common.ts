/**
 * Pieces shared by the benchmark entry points: machine description, timed
 * rendering through the same headless session as the CLI, and result files.
 */
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, readdirSync, readFileSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import type { RenderSession } from '../src/node/session';
import type { Scene } from '../src/scene/types';

/**
 * The project's root: the nearest directory above this module with a
 * package.json (this file runs from bench/ through tsx and from dist/cli/
 * when bundled).
 */
export function projectRoot(): URL {
  let dir = new URL('./', import.meta.url);
  for (let i = 0; i < 8; i++) {
    if (existsSync(new URL('package.json', dir))) return dir;
    dir = new URL('../', dir);
  }
  throw new Error('cannot find the project root (package.json) above the benchmark');
}

export const RESULTS_DIR = new URL('bench/results/', projectRoot());

export interface MachineInfo {
  cpu: string;
  cores: number;
  memoryGiB: number;
  platform: string;
  node: string;
  browser: string;
}

export async function machineInfo(session: RenderSession): Promise<MachineInfo> {
  const cpus = os.cpus();
  return {
    cpu: cpus[0]?.model ?? 'unknown',
    cores: cpus.length,
    memoryGiB: Math.round((os.totalmem() / 2 ** 30) * 10) / 10,
    platform: `${os.platform()} ${os.release()} ${os.arch()}`,
    node: process.version,
    browser: session.page.context().browser()?.version() ?? 'unknown',
  };
}

export function gitRevision(): string {
  try {
    const head = execFileSync('git', ['rev-parse', '--short', 'HEAD'], { encoding: 'utf8' }).trim();
    const dirty = execFileSync('git', ['status', '--porcelain', '--', 'src'], { encoding: 'utf8' }).trim();
    return dirty ? `${head}+dirty` : head;
  } catch {
    return 'unknown';
  }
}

export interface Throughput {
  width: number;
  height: number;
  maxBounces: number;
  /** Seconds from load to the end of the first 1-spp draw: shader compile and link included. */
  startupSeconds: number;
  spp: number;
  seconds: number;
  /** Camera paths per second (spp * width * height / seconds), in millions. */
  megaPathsPerSecond: number;
  /** Camera paths per CPU second of the GPU process (where SwiftShader runs), in millions: robust to other load. */
  megaPathsPerCpuSecond?: number;
}

/** Renders for about `seconds` after a 1-spp warm-up and reports the path rate. */
export async function measureThroughput(
  session: RenderSession,
  scene: Scene,
  size: { width: number; height: number },
  seconds: number,
  seed = 1,
): Promise<Throughput> {
  const startLoad = performance.now();
  await session.load(scene, { ...size, seed });
  await session.render(1);
  const startupSeconds = (performance.now() - startLoad) / 1000;
  const pixels = size.width * size.height;
  // Chunks of ~1 s: the loop overhead is negligible and each draw carries
  // as many samples as the session allows (as in a long CLI render).
  const { spp, seconds: elapsed, cpuSeconds } = await renderFor(session, seconds, 1);
  return {
    width: size.width,
    height: size.height,
    maxBounces: scene.render.maxBounces,
    startupSeconds,
    spp,
    seconds: elapsed,
    megaPathsPerSecond: (spp * pixels) / elapsed / 1e6,
    megaPathsPerCpuSecond: cpuSeconds === undefined ? undefined : (spp * pixels) / cpuSeconds / 1e6,
  };
}

/**
 * Renders the loaded scene for about `seconds`, in calls of about
 * `chunkSeconds` each (sized from the rate so far); returns the spp drawn,
 * the wall time and the GPU process's CPU time (when it can be read).
 */
export async function renderFor(
  session: RenderSession,
  seconds: number,
  chunkSeconds: number,
): Promise<{ spp: number; seconds: number; cpuSeconds?: number }> {
  let chunk = 1;
  let spp = 0;
  const cpuStart = gpuProcessCpuSeconds();
  const start = performance.now();
  let elapsed = 0;
  while (elapsed < seconds) {
    await session.render(chunk);
    spp += chunk;
    elapsed = (performance.now() - start) / 1000;
    const rate = spp / Math.max(elapsed, 1e-3);
    chunk = Math.max(1, Math.min(Math.round(rate * chunkSeconds), Math.ceil(rate * (seconds - elapsed))));
  }
  const cpuEnd = gpuProcessCpuSeconds();
  return { spp, seconds: elapsed, cpuSeconds: cpuStart === undefined || cpuEnd === undefined ? undefined : cpuEnd - cpuStart };
}

export function writeResult(prefix: string, data: unknown): string {
  mkdirSync(RESULTS_DIR, { recursive: true });
  const stamp = new Date().toISOString().replace(/[:.]/g, '-');
  const url = new URL(`${prefix}-${stamp}.json`, RESULTS_DIR);
  writeFileSync(url, `${JSON.stringify(data, null, 2)}\n`);
  return url.pathname;
}

/**
 * CPU seconds (user + system) used so far by the GPU process of the Chromium
 * that this Node process launched (Linux /proc only; undefined elsewhere).
 * SwiftShader renders there, so CPU time per path is a measure of our shader's
 * cost that other load on the machine barely disturbs, unlike wall time.
 */
export function gpuProcessCpuSeconds(): number | undefined {
  try {
    const pids = readdirSync('/proc').filter((d) => /^\d+$/.test(d));
    const stat = (pid: string) => readFileSync(`/proc/${pid}/stat`, 'utf8');
    const ppid = (s: string) => Number(s.slice(s.lastIndexOf(')') + 2).split(' ')[1]);
    // Every descendant of this process (the GPU process hangs off a zygote).
    const parent = new Map<string, number>();
    for (const p of pids) {
      try {
        parent.set(p, ppid(stat(p)));
      } catch {
        // the process ended meanwhile
      }
    }
    const mine = new Set<string>([String(process.pid)]);
    for (let grew = true; grew; ) {
      grew = false;
      for (const [p, pp] of parent) if (!mine.has(p) && mine.has(String(pp))) (mine.add(p), (grew = true));
    }
    const ticks = 100; // USER_HZ on Linux
    let total: number | undefined;
    for (const pid of mine) {
      try {
        if (!readFileSync(`/proc/${pid}/cmdline`, 'utf8').includes('--type=gpu-process')) continue;
        const s = stat(pid);
        const fields = s.slice(s.lastIndexOf(')') + 2).split(' ');
        total = (total ?? 0) + (Number(fields[11]) + Number(fields[12])) / ticks;
      } catch {
        // the process ended meanwhile
      }
    }
    return total;
  } catch {
    return undefined;
  }
}
