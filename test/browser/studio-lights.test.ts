/**
 * The version-3 lights against closed forms, on a white Lambert ground
 * (albedo 1: reflected radiance = irradiance / pi) with nothing else in the
 * scene (the sky black, so only direct light counts):
 *   - a directional light of irradiance E straight down: E / pi in every
 *     pixel, exactly (a delta light and a Lambert plane: no noise at all);
 *   - a point light of intensity I at height d: I cos^3(theta) / (pi d^2)
 *     at each ground point, for d and 2 d (the fall-off as 1 / d^2);
 *   - a spot straight down: the same times Mitsuba's fall-off (1 inside
 *     the beam, linear in angle to 0 at the cutoff), computed here on its own;
 *   - a disk and a rectangle of radiance L facing the ground: at the point
 *     under their centre, L times the form factor (disk R^2 / (h^2 + R^2);
 *     rectangle: four corner form factors, Howell's catalog), through
 *     next-event estimation and BSDF hits weighted by MIS together.
 * The expected image of the delta lights is the closed form averaged over
 * each pixel (4 x 4 positions), so only the pixel jitter's noise remains.
 * And every kind of light inside a closed glass mesh and a glass sphere
 * renders without NaN, Inf or rejected samples.
 */
import { describe, expect, it } from 'vitest';
import { cameraRay } from '../../src/scene/camera';
import { parseScene } from '../../src/scene/schema';
import type { Scene, Vec3 } from '../../src/scene/types';
import { fixtureFiles, useRenderSession } from '../support/browser';

const WHITE_GROUND = { height: 0, material: { color: [1, 1, 1], roughness: 1 } };
const groundScene = (lights: unknown[], camera: unknown, size = { width: 32, height: 24 }) =>
  parseScene({ version: 3, image: size, render: { maxBounces: 1 }, camera, environment: null, ground: WHITE_GROUND, lights });

/** Per pixel, the mean of `radiance` over 4 x 4 positions of the ground point the camera ray meets (row 0 at the top). */
function expectedImage(scene: Scene, radiance: (p: Vec3) => number): Float64Array {
  const { width, height } = scene.image;
  const out = new Float64Array(width * height);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      let sum = 0;
      for (let s = 0; s < 16; s++) {
        const ray = cameraRay(scene.camera, width / height, (x + ((s % 4) + 0.5) / 4) / width, (y + (Math.floor(s / 4) + 0.5) / 4) / height);
        const t = -ray.origin[1] / ray.direction[1];
        sum += t > 0 ? radiance(ray.origin.map((o, k) => o + t * ray.direction[k]) as Vec3) : 0;
      }
      out[y * width + x] = sum / 16;
    }
  }
  return out;
}

/** Spot fall-off as Mitsuba's spot.cpp defines it (angles in degrees). */
function spotFalloff(cosTheta: number, cutoff: number, beam: number): number {
  const theta = (Math.acos(Math.min(1, cosTheta)) * 180) / Math.PI;
  if (theta >= cutoff) return 0;
  return theta <= beam ? 1 : (cutoff - theta) / (cutoff - beam);
}

/** Rendered channel 0 per pixel against `expected`: the largest relative error where expected is above 2% of its maximum. */
function worstError(data: Float32Array, expected: Float64Array): number {
  const max = Math.max(...expected);
  let worst = 0;
  for (let p = 0; p < expected.length; p++) {
    if (expected[p] < 0.02 * max) expect(Math.abs(data[p * 4] - expected[p])).toBeLessThan(0.02 * max);
    else worst = Math.max(worst, Math.abs(data[p * 4] / expected[p] - 1));
  }
  return worst;
}

/** Sum of the rendered channel 0 over the sum of `expected`. */
function meanRatio(data: Float32Array, expected: Float64Array): number {
  let sum = 0;
  for (let p = 0; p < expected.length; p++) sum += data[p * 4];
  return sum / expected.reduce((a, b) => a + b, 0);
}

describe('studio lights against closed forms on a white Lambert plane', () => {
  const session = useRenderSession();
  const render = async (scene: Scene, spp: number) => {
    await session().load(scene, { ...scene.image, seed: 1 });
    expect(await session().render(spp)).toBe(spp);
    return session().readLinear();
  };
  const oblique = { position: [0, 3, 4], target: [0, 0, 0], fov: 60 };

  it('a directional light of irradiance E facing the plane gives E / pi everywhere, exactly', async () => {
    const data = await render(groundScene([{ type: 'directional', direction: [0, -3, 0], irradiance: 2.5 }], oblique), 4);
    for (let p = 0; p < data.length / 4; p++) {
      for (let c = 0; c < 3; c++) expect(data[p * 4 + c] / (2.5 / Math.PI) - 1).toBeCloseTo(0, 5);
    }
  });

  it('a point light gives I cos^3 / (pi d^2): its irradiance falls as 1 / d^2', async () => {
    for (const d of [1, 2]) {
      const scene = groundScene([{ type: 'point', position: [0.3, d, 0.2], intensity: 5 }], oblique);
      const expected = expectedImage(scene, (p) => {
        const r2 = (p[0] - 0.3) ** 2 + d * d + (p[2] - 0.2) ** 2;
        return (5 * (d / Math.sqrt(r2))) / r2 / Math.PI;
      });
      const data = await render(scene, 64);
      // Far pixels span a lot of ground: 64 jittered positions leave ~1-2% noise there.
      expect(worstError(data, expected), `d = ${d}`).toBeLessThan(0.04);
      expect(meanRatio(data, expected) - 1, `d = ${d}`).toBeCloseTo(0, 3);
    }
  });

  it("a spot straight down gives the point light's radiance times Mitsuba's fall-off", async () => {
    const [cutoff, beam, h] = [35, 20, 1.5];
    const scene = groundScene([{ type: 'spot', position: [0, h, 0], target: [0, 0, 0], intensity: 6, cutoffAngle: cutoff, beamWidth: beam }], {
      position: [0, 4, 1.5],
      target: [0, 0, 0],
      fov: 50,
    });
    const expected = expectedImage(scene, (p) => {
      const r2 = p[0] * p[0] + h * h + p[2] * p[2];
      const cos = h / Math.sqrt(r2);
      return (6 * cos * spotFalloff(cos, cutoff, beam)) / r2 / Math.PI;
    });
    const data = await render(scene, 64);
    expect(expected.filter((e) => e > 0).length, 'pixels lit by the spot').toBeGreaterThan(100);
    expect(expected.filter((e) => e === 0).length, 'pixels outside the cone').toBeGreaterThan(100);
    // Pixels across the kinks at the beam and the cutoff average a kink,
    // which 4 x 4 positions resolve to a few % of the peak: compared in
    // units of the peak there, relatively inside the beam.
    const peak = Math.max(...expected);
    let worstInBeam = 0;
    for (let p = 0; p < expected.length; p++) {
      expect(Math.abs(data[p * 4] - expected[p]) / peak, `pixel ${p}`).toBeLessThan(0.03);
      if (expected[p] > 0.9 * peak) worstInBeam = Math.max(worstInBeam, Math.abs(data[p * 4] / expected[p] - 1));
    }
    expect(worstInBeam).toBeLessThan(0.01);
    expect(Math.abs(meanRatio(data, expected) - 1)).toBeLessThan(0.002);
  });

  // Looking steeply down at the point under the light (1 degree of view spans 0.01 units of ground there).
  const under = { position: [0, 0.5, 0.15], target: [0, 0, 0], fov: 1 };
  /** The mean of a small render of the point under the camera's target and its standard error (pixels are independent estimates). */
  async function meanAndError(scene: Scene, spp: number): Promise<[number, number]> {
    const data = await render(scene, spp);
    const values = Array.from({ length: data.length / 4 }, (_, p) => data[p * 4]);
    const mean = values.reduce((a, b) => a + b, 0) / values.length;
    const variance = values.reduce((a, b) => a + (b - mean) ** 2, 0) / (values.length - 1);
    return [mean, Math.sqrt(variance / values.length)];
  }

  it('a disk of radiance L at height h gives L R^2 / (h^2 + R^2) under its centre', async () => {
    const [h, R, L] = [1, 0.6, 3];
    const scene = groundScene([{ type: 'disk', position: [0, h, 0], radius: R, intensity: L }], under, { width: 16, height: 16 });
    const [mean, error] = await meanAndError(scene, 128);
    const expected = (L * R * R) / (h * h + R * R);
    expect(Math.abs(mean - expected), `${mean} vs ${expected} (standard error ${error})`).toBeLessThan(4 * error + 5e-4 * expected);
    expect(error / expected).toBeLessThan(0.005);
  });

  it('a rectangle of radiance L gives L times its form factor under its centre (tilted rectangles are the reference scenes)', async () => {
    const [h, w, l, L] = [0.8, 1.2, 0.5, 4];
    const corner = (a: number, b: number) => {
      const [x, y] = [a / h, b / h];
      return (1 / (2 * Math.PI)) * ((x / Math.hypot(1, x)) * Math.atan(y / Math.hypot(1, x)) + (y / Math.hypot(1, y)) * Math.atan(x / Math.hypot(1, y)));
    };
    const scene = groundScene([{ type: 'rectangle', position: [0, h, 0], size: [w, l], intensity: L }], under, { width: 16, height: 16 });
    const [mean, error] = await meanAndError(scene, 128);
    const expected = L * 4 * corner(w / 2, l / 2);
    expect(Math.abs(mean - expected), `${mean} vs ${expected} (standard error ${error})`).toBeLessThan(4 * error + 5e-4 * expected);
    expect(error / expected).toBeLessThan(0.005);
  });

  it('every kind of light inside a closed glass mesh and a glass sphere renders without NaN, Inf or rejected samples', async () => {
    const glass = { type: 'dielectric', ior: 1.5 };
    const scene = parseScene({
      version: 3,
      image: { width: 24, height: 16 },
      camera: { position: [0, 1, 5], target: [0, 0.6, 0], fov: 50 },
      environment: { color: [0.2, 0.3, 0.5], intensity: 0.2 },
      ground: { height: 0, material: { color: [0.8, 0.8, 0.8], roughness: 1 } },
      meshes: [{ file: '../meshes/ico-smooth.obj', material: glass, position: [-1, 0.8, 0], scale: 0.7 }],
      spheres: [{ center: [1, 0.8, 0], radius: 0.7, material: glass }],
      lights: [
        { type: 'rectangle', position: [-1, 0.8, 0], rotation: [20, 0, 10], size: [0.3, 0.2], intensity: 20 },
        { type: 'point', position: [-1.1, 0.9, 0.1], intensity: 5 },
        { type: 'disk', position: [1, 0.8, 0], rotation: [-10, 0, 30], radius: 0.2, intensity: 20 },
        { type: 'spot', position: [1, 0.9, 0], target: [1, 0, 0], intensity: 10, cutoffAngle: 60 },
        { type: 'sphere', position: [1.1, 0.7, 0.1], radius: 0.05, intensity: 50 },
        { type: 'directional', direction: [0.2, -1, -0.3], irradiance: 1 },
      ],
    });
    await session().load(scene, { ...scene.image, seed: 1 }, fixtureFiles(scene));
    expect(await session().render(32)).toBe(32);
    const data = await session().readLinear();
    let lit = 0;
    for (let p = 0; p < data.length / 4; p++) {
      for (let c = 0; c < 3; c++) expect(Number.isFinite(data[p * 4 + c]) && data[p * 4 + c] >= 0, `pixel ${p}`).toBe(true);
      expect(data[p * 4 + 3], `pixel ${p}: rejected samples`).toBe(0);
      if (data[p * 4] > 0.01) lit++;
    }
    expect(lit).toBeGreaterThan(data.length / 8);
  });
});
