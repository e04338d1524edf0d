/**
 * Numerical robustness: valid but nasty scenes, each rendered small for a few
 * dozen samples per pixel. Whatever the scene, no pixel may be NaN, infinite
 * or negative, and the shader must not have rejected a single sample (the
 * alpha channel of readLinear() is the fraction of rejected samples). Nor
 * may the image be all black or constant: a shader that gave up (wrote 0,
 * or one colour everywhere) would pass the finiteness checks alone. Each
 * case sees lit geometry or a light, and Monte Carlo noise alone makes pixels
 * differ, so a spread (max - min) below 1e-3 of the maximum is a failure.
 *
 * Degenerate cameras that cannot be rendered as asked are decided by the
 * parser (docs/scene-format.md, docs/limits-and-errors.md): `up` parallel to
 * the view is accepted (camera.ts falls back to another up), a zero `up`,
 * `target == position` and `focusDistance <= 0` are rejected with a message.
 */
import { describe, expect, it } from 'vitest';
import { parseScene, safeParseScene } from '../../src/scene/schema';
import type { Scene } from '../../src/scene/types';
import { useRenderSession } from '../support/browser';

const SIZE = { width: 12, height: 9 };
const SPP = 24;

type Json = Record<string, unknown>;

/** A lit, bounded scene around the origin that the nasty cases edit. */
function base(): Json {
  return {
    camera: { position: [0, 1, 5], target: [0, 0.5, 0], fov: 50 },
    environment: { color: [0.4, 0.5, 0.7], intensity: 0.5 },
    ground: { height: 0, material: { color: [0.8, 0.8, 0.8], roughness: 1 } },
    lights: [{ position: [2, 4, 2], radius: 0.5, intensity: 20 }],
    spheres: [
      { center: [0, 0.5, 0], radius: 0.5, material: { color: [0.9, 0.2, 0.2], roughness: 0.5 } },
      { center: [1.2, 0.5, -0.5], radius: 0.5, material: { color: [0.9, 0.9, 0.9], roughness: 0 } },
    ],
  };
}

function offset(p: number[], d: number[]): number[] {
  return p.map((x, i) => x + d[i]);
}

/** The same scene translated by `d`: camera, lights, spheres and ground. */
function translated(scene: Json, d: number[]): Json {
  const camera = scene.camera as Json;
  return {
    ...scene,
    camera: { ...camera, position: offset(camera.position as number[], d), target: offset(camera.target as number[], d) },
    ground: { ...(scene.ground as Json), height: ((scene.ground as Json).height as number) + d[1] },
    lights: (scene.lights as Json[]).map((l) => ({ ...l, position: offset(l.position as number[], d) })),
    spheres: (scene.spheres as Json[]).map((s) => ({ ...s, center: offset(s.center as number[], d) })),
  };
}

function withMaterial(roughness: number): Json {
  const b = base();
  b.spheres = (b.spheres as Json[]).map((s) => ({ ...s, material: { color: [0.95, 0.95, 0.95], roughness } }));
  b.ground = { height: 0, material: { color: [0.7, 0.7, 0.7], roughness } };
  return b;
}

const NASTY: [string, Json][] = [
  // Version 3 lights at their edge cases: a rectangle lying in the ground
  // plane (every ground point on its plane), one whose edge touches a
  // sphere, a spot of cutoff 90 with no transition, one whose target is a
  // hair away, a directional light travelling up (away from the ground), a
  // point light on a sphere's surface, huge and tiny planar lights.
  ['v3 lights at their edge cases', { ...base(), version: 3, lights: [
    { type: 'rectangle', position: [0.5, 0, 0.5], size: [1, 1], intensity: 5 },
    { type: 'rectangle', position: [0, 1.0, 0], rotation: [90, 0, 0], size: [0.5, 1e-3], intensity: 5 },
    { type: 'disk', position: [0, 3, 0], radius: 1e5, intensity: 0.01 },
    { type: 'disk', position: [-1, 2, 1], radius: 1e-4, intensity: 1e6 },
    { type: 'spot', position: [0, 2, 0], target: [0, 0, 0], cutoffAngle: 90, beamWidth: 90, intensity: 5 },
    { type: 'spot', position: [1, 2, 0], target: [1, 2 - 1e-5, 0], cutoffAngle: 1e-3, beamWidth: 0, intensity: 5 },
    { type: 'directional', direction: [0, 1, 0], irradiance: 3 },
    { type: 'directional', direction: [1e-5, -1, 0], irradiance: 1 },
    { type: 'point', position: [0, 1, 0], intensity: 2 },
  ] }],
  ['overlapping spheres', { ...base(), spheres: [
    { center: [0, 0.5, 0], radius: 0.6, material: { roughness: 1 } },
    { center: [0.3, 0.6, 0.1], radius: 0.6, material: { roughness: 0 } },
    { center: [0, 0.5, 0], radius: 0.6, material: { roughness: 0.3 } }, // coincident with the first
    { center: [-0.2, 0.4, 0.2], radius: 0.2, material: { roughness: 0.5 } }, // inside the first
  ] }],
  ['camera inside a diffuse sphere, light inside too', { ...base(),
    spheres: [{ center: [0, 1, 4], radius: 3, material: { color: [0.9, 0.9, 0.9], roughness: 1 } }],
    lights: [{ position: [0, 2, 3], radius: 0.3, intensity: 30 }] }],
  ['camera inside a mirror sphere', { ...base(),
    spheres: [{ center: [0, 1, 5], radius: 1, material: { color: [1, 1, 1], roughness: 0 } }] }],
  ['camera inside a light', { ...base(), lights: [{ position: [0, 1, 5], radius: 1, intensity: 5 }] }],
  ['light inside a sphere', { ...base(), lights: [{ position: [0, 0.5, 0], radius: 0.2, intensity: 50 }] }],
  ['light touching the ground', { ...base(), lights: [{ position: [0.5, 0.3, 1], radius: 0.3, intensity: 40 }] }],
  ['light cut by the ground', { ...base(), lights: [{ position: [0.5, 0.1, 1], radius: 0.3, intensity: 40 }] }],
  ['light touching a sphere', { ...base(), lights: [{ position: [0, 1.25, 0], radius: 0.25, intensity: 40 }] }],
  ['radii 1e-4 and 1e4', { ...base(), spheres: [
    { center: [0, 0.5, 4.99], radius: 1e-4, material: { roughness: 0 } },
    { center: [0, 0.5, 0], radius: 1e-4 },
    { center: [0, -1e4, 0], radius: 1e4, material: { color: [0.5, 0.8, 0.5], roughness: 0.2 } },
    { center: [0, 0, -2e4], radius: 1e4, material: { roughness: 1 } },
  ], lights: [{ position: [1, 2, 1], radius: 1e-4, intensity: 1e9 }, { position: [0, 3e4, 0], radius: 1e4, intensity: 0.5 }] }],
  ['coordinates near 1e5', translated(base(), [1e5, 1e5, -1e5])],
  ['coordinates at the limit 1e6', translated(base(), [1e6 - 10, 0, 1e6 - 10])],
  ['looking straight down, default up', { ...base(), camera: { position: [0, 6, 0], target: [0, 0, 0] } }],
  ['looking straight up, default up', { ...base(), camera: { position: [0, 0.5, 0.5], target: [0, 10, 0.5] } }],
  ['up parallel to a sideways view', { ...base(), camera: { position: [0, 1, 5], target: [0, 1, 0], up: [0, 0, 3] } }],
  ['camera exactly on the ground plane', { ...base(), camera: { position: [0, 0, 5], target: [0, 0, 0] } }],
  ['roughness exactly 0', withMaterial(0)],
  ['roughness 1e-6', withMaterial(1e-6)],
  ['roughness exactly 1', withMaterial(1)],
  ['roughness 1e-3', withMaterial(1e-3)],
  ['zero intensities everywhere', { ...base(), environment: { intensity: 0 }, lights: [{ position: [2, 4, 2], radius: 0.5, intensity: 0 }] }],
  ['huge intensities (1e12)', { ...base(), environment: { color: [1, 1, 1], intensity: 1e12 },
    lights: [{ position: [2, 4, 2], radius: 0.5, intensity: 1e12 }] }],
  ['huge emission: color and intensity at the limit', { ...base(), environment: null,
    lights: [{ position: [0, 1, 2], radius: 0.5, color: [1e12, 1e12, 1e12], intensity: 1e12 }] }],
  ['maxBounces 0', { ...base(), render: { maxBounces: 0 } }],
  ['maxBounces 64 between mirrors', { ...base(), render: { maxBounces: 64 },
    environment: { intensity: 1 },
    spheres: [
      { center: [0, 0.5, -3], radius: 2, material: { color: [1, 1, 1], roughness: 0 } },
      { center: [0, 0.5, 8], radius: 2, material: { color: [1, 1, 1], roughness: 0 } },
      { center: [0, 0.5, 0], radius: 0.5, material: { color: [1, 1, 1], roughness: 1e-6 } },
    ] }],
  ['aperture with focus distance 1e-6', { ...base(), camera: { position: [0, 1, 5], target: [0, 0.5, 0], aperture: 0.5, focusDistance: 1e-6 } }],
  ['huge aperture, huge focus distance', { ...base(), camera: { position: [0, 1, 5], target: [0, 0.5, 0], aperture: 1e6, focusDistance: 1e7 } }],
  ['fov near 0 and near 180', { ...base(), camera: { position: [0, 1, 5], target: [0, 0.5, 0], fov: 1e-3 } }],
  ['fov 179.999', { ...base(), camera: { position: [0, 1, 5], target: [0, 0.5, 0], fov: 179.999 } }],
  ['16 lights and 128 spheres', { ...base(),
    lights: Array.from({ length: 16 }, (_, i) => ({ position: [i - 8, 3, -i * 0.5], radius: 0.1 + i * 0.05, intensity: 10 + i })),
    spheres: Array.from({ length: 128 }, (_, i) => ({
      center: [(i % 16) - 8, 0.2 + Math.floor(i / 16) * 0.1, -Math.floor(i / 16)],
      radius: 0.3,
      material: { roughness: (i % 5) / 4 },
    })) }],
];

interface Summary {
  nonFinite: number;
  negative: number;
  rejected: number;
  max: number;
  min: number;
  first: string;
}

function summarize(data: Float32Array): Summary {
  const s: Summary = { nonFinite: 0, negative: 0, rejected: 0, max: 0, min: Infinity, first: '' };
  for (let p = 0; p < data.length / 4; p++) {
    for (let c = 0; c < 3; c++) {
      const v = data[p * 4 + c];
      if (!Number.isFinite(v)) s.nonFinite++;
      else if (v < 0) s.negative++;
      else {
        s.max = Math.max(s.max, v);
        s.min = Math.min(s.min, v);
      }
      if ((!Number.isFinite(v) || v < 0) && !s.first) s.first = `pixel ${p} channel ${c} = ${v}`;
    }
    const a = data[p * 4 + 3];
    if (a !== 0) {
      s.rejected++;
      if (!s.first) s.first = `pixel ${p}: ${a} of its samples rejected`;
    }
  }
  return s;
}

describe('nasty but valid scenes render without NaN, Inf, negative or rejected samples', () => {
  const session = useRenderSession();

  it('every case is a valid scene', () => {
    for (const [name, json] of NASTY) {
      const result = safeParseScene(json);
      expect(result.ok ? [] : result.issues, name).toEqual([]);
    }
  });

  // The huge-emission case is separate (below): a regression test of a fixed bug.
  it.each(NASTY.filter(([name]) => !name.startsWith('huge emission')))('%s', async (name, json) => {
    const scene: Scene = parseScene(json);
    await session().load(scene, { ...SIZE, seed: 1 });
    expect(await session().render(SPP)).toBe(SPP);
    const s = summarize(await session().readLinear());
    expect(s, `${name}: ${s.first}`).toMatchObject({ nonFinite: 0, negative: 0, rejected: 0 });
    expectLitAndVaried(name, s);
  });

  it('sanity: the checks see light (the base scene is not black)', async () => {
    await session().load(parseScene(base()), { ...SIZE, seed: 1 });
    await session().render(SPP);
    expect(summarize(await session().readLinear()).max).toBeGreaterThan(0.05);
  });

  // Precision far from the origin: the same scene moved by 1e5 must look the
  // same (self-intersection "acne" or lost intersections would darken or
  // speckle it). Means over the image agree within their Monte Carlo noise.
  it('a scene moved to 1e5 renders like the original (image mean within 5%)', async () => {
    const means: number[] = [];
    for (const json of [base(), translated(base(), [1e5, 1e5, -1e5])]) {
      await session().load(parseScene(json), { width: 16, height: 12, seed: 5 });
      await session().render(96);
      const data = await session().readLinear();
      let sum = 0;
      for (let i = 0; i < data.length; i += 4) sum += data[i] + data[i + 1] + data[i + 2];
      means.push(sum / (data.length / 4) / 3);
    }
    expect(means[0]).toBeGreaterThan(0.05);
    expect(Math.abs(means[1] / means[0] - 1), `means ${means}`).toBeLessThan(0.05);
  });

  // Regression (found by this file, fixed in 6f13452): the format allows
  // emitted radiance color * intensity up to 1e12 * 1e12 = 1e24, but
  // trace.frag rejected every sample >= MAX_RADIANCE, then 1e20. It is now
  // 1e30 (src/render/sampling.ts); float32 still sums 1e8 such samples.
  it('huge emission at the limit (1e12 * 1e12) is not rejected (MAX_RADIANCE above the largest emission of the format)', async () => {
    const [, json] = NASTY.find(([name]) => name.startsWith('huge emission'))!;
    await session().load(parseScene(json), { ...SIZE, seed: 1 });
    await session().render(SPP);
    const s = summarize(await session().readLinear());
    expect(s, s.first).toMatchObject({ nonFinite: 0, negative: 0, rejected: 0 });
    expectLitAndVaried('huge emission', s);
  });
});

/**
 * Cases whose exact image is black, as in Mitsuba: inside a one-sided mirror
 * sphere nothing reflects and nothing gets in; inside a light (emitting
 * outward only, reflecting nothing) likewise; zero emission everywhere.
 * Every other case must show light and noise.
 */
const EXPECTED_BLACK = new Set(['camera inside a mirror sphere', 'camera inside a light', 'zero intensities everywhere']);

function expectLitAndVaried(name: string, s: Summary): void {
  if (EXPECTED_BLACK.has(name)) {
    expect(s.max, `${name}: must be exactly black`).toBe(0);
    return;
  }
  expect(s.max, `${name}: the image is all black`).toBeGreaterThan(0);
  expect(s.max - s.min, `${name}: the image is constant (min ${s.min}, max ${s.max})`).toBeGreaterThan(1e-3 * s.max);
}

describe('degenerate cameras the parser rejects, with a clear message', () => {
  const camera = (extra: Json) => ({ camera: { position: [0, 1, 5], target: [0, 0, 0], ...extra } });
  it.each([
    ['target equal to position', { target: [0, 1, 5] }, 'camera.target', 'must differ from camera.position'],
    ['target within 1e-6 of position', { target: [0, 1, 5 + 1e-7] }, 'camera.target', 'must differ from camera.position'],
    ['zero up', { up: [0, 0, 0] }, 'camera.up', 'must not be zero length'],
    ['zero focus distance', { focusDistance: 0, aperture: 0.1 }, 'camera.focusDistance', 'must be > 0'],
    ['negative focus distance', { focusDistance: -1 }, 'camera.focusDistance', 'must be > 0'],
    ['fov 0', { fov: 0 }, 'camera.fov', 'must be > 0'],
    ['fov 180', { fov: 180 }, 'camera.fov', 'must be < 180'],
    ['negative aperture', { aperture: -0.1 }, 'camera.aperture', 'must be >= 0'],
  ])('%s', (_, extra, path, message) => {
    const result = safeParseScene(camera(extra));
    expect(result.ok ? [] : result.issues).toEqual([{ path, message }]);
  });
});
