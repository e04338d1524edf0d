/**
 * Many lights (issue 21's row): the path rate of lights.json's spheres and
 * ground lit by 64 mixed lights against the same scene lit by one
 * rectangle (the row's baseline) and by lights.json's five lights (one per
 * kind: the same kinds' code as the 64, so the ratio to it isolates the
 * cost of the count). Scenes are rendered in interleaved rounds in one
 * browser; rates are per CPU second of the GPU process.
 *
 *   npx tsx bench/many-lights.ts [--rounds 3] [--seconds 4] [--size 192x120]   (after npm run build:web)
 * `npm run bench` prints it too (runManyLights).
 */
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { openRenderSession, type RenderSession } from '../src/node/session';
import { parseScene } from '../src/scene/schema';
import type { Scene } from '../src/scene/types';
import { projectRoot, renderFor } from './common';

export interface ManyLightsResult {
  size: { width: number; height: number };
  rounds: number;
  secondsPerRun: number;
  /** Camera paths per CPU second of the GPU process, per round, in millions. */
  rates: Record<ManyLightsScene, number[]>;
  /** Medians over rounds of the 64-light rate over each baseline's (same round). */
  ratioToOne: number;
  ratioToFive: number;
}

type ManyLightsScene = 'one' | 'five' | 'sixtyFour';

/** A deterministic generator (a 32-bit LCG): the 64 lights are the same in every run. */
function random(seed: number): () => number {
  let state = seed >>> 0;
  return () => {
    state = (Math.imul(state, 1664525) + 1013904223) >>> 0;
    return state / 2 ** 32;
  };
}

/**
 * 64 lights of a studio around the objects: 13 each of rectangles, disks,
 * points and spots on a dome of radius 2.5 to 4 at heights 1.2 to 3.5, the
 * area lights and spots facing the objects, and 12 directional lights.
 */
export function sixtyFourLights(): unknown[] {
  const next = random(21);
  const onDome = () => {
    const phi = 2 * Math.PI * next();
    const r = 2.5 + 1.5 * next();
    return [r * Math.cos(phi), 1.2 + 2.3 * next(), r * Math.sin(phi)];
  };
  const color = () => [0.6 + 0.4 * next(), 0.6 + 0.4 * next(), 0.6 + 0.4 * next()];
  // Rotation that turns the emitting axis (-y) towards the origin: pitch about x, then yaw about y.
  const facing = (p: number[]) => {
    const [x, y, z] = p.map((c) => -c);
    const len = Math.hypot(x, y, z);
    const pitch = (Math.acos(-y / len) * 180) / Math.PI; // -y turned towards +z by this much
    const yaw = (Math.atan2(x, z) * 180) / Math.PI;
    return [pitch, yaw, 0];
  };
  const lights: unknown[] = [];
  for (let i = 0; i < 13; i++) {
    const p = onDome();
    lights.push({ type: 'rectangle', position: p, rotation: facing(p), size: [0.4 + 0.4 * next(), 0.3 + 0.3 * next()], color: color(), intensity: 1.5 });
  }
  for (let i = 0; i < 13; i++) {
    const p = onDome();
    lights.push({ type: 'disk', position: p, rotation: facing(p), radius: 0.15 + 0.15 * next(), color: color(), intensity: 4 });
  }
  for (let i = 0; i < 13; i++) lights.push({ type: 'point', position: onDome(), color: color(), intensity: 0.4 });
  for (let i = 0; i < 13; i++) {
    const target = [next() - 0.5, 0, next() - 0.5];
    lights.push({ type: 'spot', position: onDome(), target, cutoffAngle: 20 + 15 * next(), beamWidth: 10, color: color(), intensity: 2 });
  }
  for (let i = 0; i < 12; i++) lights.push({ type: 'directional', direction: [next() - 0.5, -1, next() - 0.5], color: color(), irradiance: 0.03 });
  return lights;
}

export function manyLightsScenes(): Record<ManyLightsScene, Scene> {
  const path = fileURLToPath(new URL('test/fixtures/scenes/lights.json', projectRoot()));
  const base = JSON.parse(readFileSync(path, 'utf8')) as { lights: unknown[] };
  const withLights = (lights: unknown[]) => parseScene({ ...base, lights });
  return { one: withLights([base.lights[0]]), five: withLights(base.lights), sixtyFour: withLights(sixtyFourLights()) };
}

async function rate(session: RenderSession, scene: Scene, size: { width: number; height: number }, seconds: number): Promise<number> {
  await session.load(scene, { ...size, seed: 1 }, {});
  await session.render(1); // compile and warm up outside the clock
  const run = await renderFor(session, seconds, 0.5);
  return (run.spp * size.width * size.height) / (run.cpuSeconds ?? run.seconds) / 1e6;
}

export async function runManyLights(
  options: { rounds?: number; seconds?: number; size?: { width: number; height: number } } = {},
  log: (line: string) => void = () => {},
): Promise<ManyLightsResult> {
  const rounds = options.rounds ?? 3;
  const seconds = options.seconds ?? 4;
  const size = options.size ?? { width: 192, height: 120 };
  const scenes = manyLightsScenes();
  const rates: Record<ManyLightsScene, number[]> = { one: [], five: [], sixtyFour: [] };
  const session = await openRenderSession({});
  try {
    for (let round = 0; round < rounds; round++) {
      for (const name of ['one', 'five', 'sixtyFour'] as const) rates[name].push(await rate(session, scenes[name], size, seconds));
      log(`many lights, round ${round + 1}: one ${rates.one[round].toFixed(3)}, five ${rates.five[round].toFixed(3)}, 64 ${rates.sixtyFour[round].toFixed(3)} M paths per CPU-s`);
    }
  } finally {
    await session.close();
  }
  const median = (v: number[]) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];
  const ratio = (base: ManyLightsScene) => median(rates.sixtyFour.map((r, i) => r / rates[base][i]));
  return { size, rounds, secondsPerRun: seconds, rates, ratioToOne: ratio('one'), ratioToFive: ratio('five') };
}

export function formatManyLights(r: ManyLightsResult): string {
  const median = (v: number[]) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)].toFixed(3);
  return [
    `many lights (${r.size.width}x${r.size.height}, ${r.rounds} interleaved rounds of ${r.secondsPerRun} s; M paths per CPU-s, medians)`,
    '| lights | Mpath/CPU-s | 64 lights / this |',
    '| --- | --- | --- |',
    `| one rectangle | ${median(r.rates.one)} | ${r.ratioToOne.toFixed(2)} (target >= 0.8) |`,
    `| five, one per kind (lights.json) | ${median(r.rates.five)} | ${r.ratioToFive.toFixed(2)} |`,
    `| 64 mixed (13 rectangles, 13 disks, 13 points, 13 spots, 12 directional) | ${median(r.rates.sixtyFour)} | 1 |`,
  ].join('\n');
}

// Run directly (not when bundled into dist/cli/bench.js, whose import.meta.url is the bundle's).
if (/many-lights\.[cm]?[jt]s$/.test(process.argv[1] ?? '')) {
  const arg = (name: string, fallback: string) => {
    const i = process.argv.indexOf(`--${name}`);
    return i >= 0 ? process.argv[i + 1] : fallback;
  };
  const [width, height] = arg('size', '192x120').split('x').map(Number);
  const result = await runManyLights({ rounds: Number(arg('rounds', '3')), seconds: Number(arg('seconds', '4')), size: { width, height } }, (l) => console.error(l));
  console.log(formatManyLights(result));
}
