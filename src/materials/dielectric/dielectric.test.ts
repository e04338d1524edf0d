import type { Material } from '../../scene/types';
/**
 * The rough dielectric's sampler (GGX visible normals, then reflection with
 * probability F, else refraction) against its pdf, in the browser on the
 * GLSL code: a chi-square test of a histogram over the WHOLE sphere of
 * directions (the reflection and the transmission hemisphere together)
 * against the pdf integrated over each bin, for several ior, roughness and
 * view angles, from outside (wo.z > 0) and from inside (wo.z < 0, which
 * includes total internal reflection). The smooth dielectric is a Dirac
 * delta (pdf 0) and has no density to test. Roughness 0.1 (alpha 0.01),
 * whose lobes a grid over the sphere cannot resolve, is tested on caps
 * around the two lobes (last describe).
 *
 * Also: each sample's weight equals bsdfEval / bsdfPdf at the sampled direction, and its mean (a moment
 * test) equals the integral of f |cos| over the sphere: a sampler that missed
 * part of f's support, or a pdf off by a factor, fails that.
 */
import { describe, expect, it } from 'vitest';
import { chiSquareTest } from '../../../test/support/chi2';
import { useRenderSession } from '../../../test/support/browser';
import { expectedCounts, sphereBin } from '../../../test/support/sphereHistogram';

const SAMPLES_SIDE = 512; // 262,144 samples per case
/** With 8 chi-square tests here (6 + 2 on caps), the false-failure rate stays below 1e-3. */
const ALPHA = 1e-4;
const DIELECTRIC = 'dielectric';
/** The kernels' material: untinted glass, or a white standard material. */
const material = (type: string, roughness: number, ior: number) =>
  (type === DIELECTRIC ? { type: 'dielectric', color: [1, 1, 1], roughness, ior } : { type: 'standard', color: [1, 1, 1], roughness }) as Material;

interface Case { ior: number; roughness: number; theta: number }
// theta > 90: wo below the surface, i.e. inside the solid.
const CASES: Case[] = [
  { ior: 1.5, roughness: 1, theta: 45 },
  { ior: 1.5, roughness: 0.7, theta: 130 }, // inside, beyond the critical angle (41.8 deg): mostly TIR
  { ior: 1.33, roughness: 1, theta: 120 },
  { ior: 2.4, roughness: 0.3, theta: 20 },
  { ior: 2.4, roughness: 0.7, theta: 150 },
  { ior: 2.4, roughness: 1, theta: 75 },
];

describe('rough dielectric sampler agrees with its pdf', () => {
  const session = useRenderSession();

  for (const { ior, roughness, theta } of CASES) {
    it(`ior ${ior}, roughness ${roughness}, view ${theta} deg${theta > 90 ? ' (inside)' : ''}`, async () => {
      const t = (theta * Math.PI) / 180;
      const wo: [number, number, number] = [Math.sin(t), 0, Math.cos(t)];
      const params = { material: material(DIELECTRIC, roughness, ior) };
      const bins = { cosBins: 20, phiBins: 40 };
      // 32 x 32 pdf points per bin: the refraction pdf has sharp features
      // (its Jacobian's denominator nearly vanishes) that 12 x 12 midpoint
      // points missed by 0.4% of the mass (measured at r = 1, view 45 deg),
      // far above the 0.04% binomial noise; at 32 the error is 0.1%.
      const sub = 32;
      const n = SAMPLES_SIDE * SAMPLES_SIDE;
      const samples = await session().runKernel({ kernel: 'sampleMaterial', width: SAMPLES_SIDE, height: SAMPLES_SIDE, ...params, wo, seed: 9 });
      const grid = await session().runKernel({
        kernel: 'pdfMaterial', width: bins.phiBins * sub, height: bins.cosBins * sub, ...params, wo,
      });
      const { expected, mass } = expectedCounts(grid, 3, bins, sub, n);
      const observed = new Float64Array(expected.length);
      let valid = 0;
      let deltas = 0; // a rough dielectric sample is never a delta
      let reflected = 0;
      let transmitted = 0;
      for (let i = 0; i < n; i++) {
        const [x, y, z, pdf] = samples.subarray(i * 4, i * 4 + 4);
        if (pdf === -1) deltas++;
        if (pdf === 0) continue; // invalid (e.g. refracted to the wrong side of h): no pdf mass there either
        valid++;
        if (z * wo[2] > 0) reflected++;
        else transmitted++;
        observed[sphereBin(x, y, z, bins)]++;
      }
      const result = chiSquareTest(observed, expected);
      const summary = JSON.stringify({ ...result, mass, valid: valid / n, reflected: reflected / n, transmitted: transmitted / n });
      console.log(`dielectric ior ${ior} r ${roughness} theta ${theta}: ${summary}`);
      // The pdf's mass is the fraction of valid samples; binomial sd of that
      // fraction < 0.001, the midpoint rule adds < 0.5% here.
      expect(deltas).toBe(0);
      expect(Math.abs(mass - valid / n), summary).toBeLessThan(0.01);
      expect(valid / n, summary).toBeGreaterThan(0.5);
      // Both hemispheres are reached unless total internal reflection forbids it.
      expect(reflected, summary).toBeGreaterThan(0);
      if (!(theta === 130)) expect(transmitted / n, summary).toBeGreaterThan(0.01);
      expect(result.degreesOfFreedom, summary).toBeGreaterThan(20);
      expect(result.pValue, summary).toBeGreaterThan(ALPHA);
    });
  }
});

describe('BSDF sample weights', () => {
  const session = useRenderSession();
  const weightCases = [
    { type: DIELECTRIC, ior: 1.5, roughness: 1, theta: 130 },
    { type: 'standard', ior: 1.5, roughness: 0.5, theta: 30 },
  ];
  for (const { type, ior, roughness, theta } of weightCases) {
    it(`${type === DIELECTRIC ? 'dielectric' : 'standard'} ior ${ior}, roughness ${roughness}, view ${theta} deg: weight = f / pdf, mean = albedo`, async () => {
      const t = (theta * Math.PI) / 180;
      const wo: [number, number, number] = [Math.sin(t), 0, Math.cos(t)];
      const params = { material: material(type, roughness, ior) };
      const n = SAMPLES_SIDE * SAMPLES_SIDE;
      // (weight, valid, bsdfEval / bsdfPdf at the sample, pdf) per sample.
      const samples = await session().runKernel({ kernel: 'weightBsdf', width: SAMPLES_SIDE, height: SAMPLES_SIDE, ...params, wo, seed: 13 });
      let sum = 0;
      let sumSq = 0;
      let worst = 0;
      for (let i = 0; i < n; i++) {
        const [weight, valid, ratio] = samples.subarray(i * 4, i * 4 + 3);
        if (valid === 0) continue;
        worst = Math.max(worst, Math.abs(weight - ratio) / Math.max(1e-6, Math.abs(ratio)));
        sum += weight;
        sumSq += weight * weight;
      }
      const mean = sum / n;
      const sd = Math.sqrt(Math.max(0, sumSq / n - mean * mean));
      // The albedo: f |cos| (channel 0 of the pdfGuided grid) integrated over the sphere.
      const bins = { cosBins: 20, phiBins: 40 };
      const sub = 32;
      const grid = await session().runKernel({ kernel: 'pdfGuided', width: bins.phiBins * sub, height: bins.cosBins * sub, ...params, wo });
      const albedo = expectedCounts(grid, 0, bins, sub, 1).mass;
      const summary = JSON.stringify({ mean, albedo, sd, worst });
      console.log(`weights: ${summary}`);
      expect(worst, summary).toBeLessThan(1e-5);
      // 5 sigma of the sample mean, plus the midpoint rule's 0.2% (the pdf's
      // mass error measured above, the same grid).
      expect(Math.abs(mean - albedo), summary).toBeLessThan((5 * sd) / Math.sqrt(n) + 0.002 * albedo);
      expect(albedo, summary).toBeGreaterThan(0.1); // not a vacuous 0 = 0
    });
  }
});

/**
 * Roughness 0.1 (alpha 0.01): the lobes are a few hundredths of a radian
 * wide, so the pdf is integrated on grids uniform in (theta, phi) over two
 * caps, one around the mirror direction and one around the macro-surface
 * refraction (pdfCap kernel); bins are rings x sectors of each cap, and the
 * valid samples outside both caps (GGX's long tails) form one more bin whose
 * expected count is the rest. Angles from an axis are computed as
 * 2 asin(|w - axis| / 2), which keeps float32 precision near the axis.
 */
describe('rough dielectric sampler at roughness 0.1 (narrow lobes, on caps)', () => {
  const session = useRenderSession();
  type V3 = [number, number, number];
  const RINGS = 12;
  const SECTORS = 12;
  // 40 x 40 pdf points per bin: at 16 the refraction pdf's sharp features
  // (seen from inside) were integrated 0.23% too high, 8 binomial sigma.
  const CAP_SUB = 40;

  function basisAround(n: V3): [V3, V3] {
    const s = n[2] >= 0 ? 1 : -1;
    const a = -1 / (s + n[2]);
    const b = n[0] * n[1] * a;
    return [[1 + s * n[0] * n[0] * a, s * b, -s * n[0]], [b, s + n[1] * n[1] * a, -n[1]]];
  }
  function refractMacro(wo: V3, ior: number): V3 {
    const side = wo[2] > 0 ? 1 : -1;
    const etaTI = wo[2] > 0 ? 1 / ior : ior;
    const cosI = Math.abs(wo[2]);
    const cosT = Math.sqrt(1 - etaTI * etaTI * (1 - cosI * cosI));
    return [-etaTI * wo[0], -etaTI * wo[1], -etaTI * wo[2] + side * (etaTI * cosI - cosT)];
  }
  /** Cap bin of w (rings in theta, sectors in phi), or -1 outside the cap. */
  function capBin(w: V3, axis: V3, halfAngle: number): number {
    const theta = 2 * Math.asin(Math.min(1, Math.hypot(w[0] - axis[0], w[1] - axis[1], w[2] - axis[2]) / 2));
    if (theta >= halfAngle) return -1;
    const [t, b] = basisAround(axis);
    const phi = (Math.atan2(w[0] * b[0] + w[1] * b[1] + w[2] * b[2], w[0] * t[0] + w[1] * t[1] + w[2] * t[2]) + 2 * Math.PI) % (2 * Math.PI);
    return Math.min(RINGS - 1, Math.floor((theta / halfAngle) * RINGS)) * SECTORS + Math.min(SECTORS - 1, Math.floor((phi / (2 * Math.PI)) * SECTORS));
  }
  /** Expected counts per cap bin: the pdf times the cells' solid angle sin(theta) dtheta dphi. */
  function capExpected(grid: Float32Array, halfAngle: number, n: number): Float64Array {
    const width = SECTORS * CAP_SUB;
    const height = RINGS * CAP_SUB;
    const expected = new Float64Array(RINGS * SECTORS);
    for (let gy = 0; gy < height; gy++) {
      const theta = ((gy + 0.5) / height) * halfAngle;
      const cell = Math.sin(theta) * (halfAngle / height) * ((2 * Math.PI) / width);
      for (let gx = 0; gx < width; gx++) {
        expected[Math.floor(gy / CAP_SUB) * SECTORS + Math.floor(gx / CAP_SUB)] += grid[(gy * width + gx) * 4 + 3] * cell * n;
      }
    }
    return expected;
  }

  const cases = [
    { ior: 1.5, theta: 30, reflectionCap: 0.12, refractionCap: 0.05 },
    { ior: 1.33, theta: 160, reflectionCap: 0.12, refractionCap: 0.12 },
  ];
  for (const { ior, theta, reflectionCap, refractionCap } of cases) {
    it(`ior ${ior}, roughness 0.1, view ${theta} deg${theta > 90 ? ' (inside)' : ''}`, async () => {
      const t = (theta * Math.PI) / 180;
      const wo: V3 = [Math.sin(t), 0, Math.cos(t)];
      const params = { material: material(DIELECTRIC, 0.1, ior) };
      const n = SAMPLES_SIDE * SAMPLES_SIDE;
      const caps: { axis: V3; halfAngle: number }[] = [
        { axis: [-wo[0], -wo[1], wo[2]], halfAngle: reflectionCap },
        { axis: refractMacro(wo, ior), halfAngle: refractionCap },
      ];
      const expectedParts: Float64Array[] = [];
      for (const cap of caps) {
        const grid = await session().runKernel({
          kernel: 'pdfCap', width: SECTORS * CAP_SUB, height: RINGS * CAP_SUB, ...params, wo, cap: [...cap.axis, cap.halfAngle],
        });
        expectedParts.push(capExpected(grid, cap.halfAngle, n));
      }
      const samples = await session().runKernel({ kernel: 'sampleMaterial', width: SAMPLES_SIDE, height: SAMPLES_SIDE, ...params, wo, seed: 17 });
      const bins = RINGS * SECTORS;
      const observed = new Float64Array(2 * bins + 1);
      let valid = 0;
      for (let i = 0; i < n; i++) {
        const [x, y, z, pdf] = samples.subarray(i * 4, i * 4 + 4);
        if (pdf <= 0) continue;
        valid++;
        const w: V3 = [x, y, z];
        const inReflection = capBin(w, caps[0].axis, caps[0].halfAngle);
        const inRefraction = inReflection < 0 ? capBin(w, caps[1].axis, caps[1].halfAngle) : -1;
        observed[inReflection >= 0 ? inReflection : inRefraction >= 0 ? bins + inRefraction : 2 * bins]++;
      }
      const expected = new Float64Array(2 * bins + 1);
      expected.set(expectedParts[0], 0);
      expected.set(expectedParts[1], bins);
      const inCaps = expected.reduce((s, v) => s + v, 0);
      expected[2 * bins] = Math.max(0, valid - inCaps);
      const result = chiSquareTest(observed, expected);
      const sum = (a: Float64Array, from: number) => a.subarray(from, from + bins).reduce((s, v) => s + v, 0) / n;
      const capTotals = { reflection: [sum(observed, 0), sum(expected, 0)], refraction: [sum(observed, bins), sum(expected, bins)] };
      const summary = JSON.stringify({ ...result, valid: valid / n, inCaps: inCaps / n, outside: observed[2 * bins] / n, capTotals });
      console.log(`dielectric r 0.1 ior ${ior} theta ${theta}: ${summary}`);
      // The caps hold most of both lobes, so the test sees their shape.
      expect(inCaps / n, summary).toBeGreaterThan(0.8);
      expect(result.degreesOfFreedom, summary).toBeGreaterThan(50);
      expect(result.pValue, summary).toBeGreaterThan(ALPHA);
    });
  }
});
