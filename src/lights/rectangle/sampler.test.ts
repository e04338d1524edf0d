/**
 * The rectangle light's sampler (rectangle.glsl, run on the real GLSL
 * through the test kernels) against its pdf, as Mitsuba tests its
 * emitters: a chi-square test of where its points land on the rectangle
 * (16 x 16 cells) against the counts its density predicts, computed here in
 * double precision (a cell's share of the solid angle when sampling by
 * solid angle, of the area when by area); the density it reports against
 * rectanglePdf (the MIS weight of a BSDF hit) and against 1 / solid angle;
 * and the mean of 1 / pdf against the solid angle, which every sampler of
 * the rectangle must give (the solid-angle sampler's pdf is the area
 * sampler's converted to solid angle: the same irradiance).
 */
import { describe, expect, it } from 'vitest';
import { chiSquareTest } from '../../../test/support/chi2';
import { useRenderSession } from '../../../test/support/browser';

type V = [number, number, number];
const SIDE = 256; // 65,536 samples per viewpoint (256 per cell on average)
const CELLS = 16;
const ALPHA = 1e-4;
const [c, u, v]: V[] = [[0, 1, 0], [0.6, 0, 0], [0, 0, 0.3]];
const MIN_SOLID_ANGLE = 1e-2; // rectangle.glsl's RECTANGLE_MIN_SOLID_ANGLE
const MAX_SOLID_ANGLE = 6.22;

const sub = (a: V, b: V): V => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a: V, b: V) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a: V, b: V): V => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const len = (a: V) => Math.sqrt(dot(a, a));
const at = (a: number, b: number): V => [0, 1, 2].map((k) => c[k] + a * u[k] + b * v[k]) as V;

function triangleSolidAngle(a: V, b: V, d: V): number {
  const [la, lb, ld] = [len(a), len(b), len(d)];
  return 2 * Math.atan2(Math.abs(dot(a, cross(b, d))), la * lb * ld + dot(a, b) * ld + dot(a, d) * lb + dot(b, d) * la);
}
/** Solid angle at x of the part [a0, a1] x [b0, b1] of the rectangle (plane coordinates). */
function solidAngle(x: V, a0 = -1, a1 = 1, b0 = -1, b1 = 1): number {
  const [p00, p10, p11, p01] = [at(a0, b0), at(a1, b0), at(a1, b1), at(a0, b1)].map((p) => sub(p, x));
  return triangleSolidAngle(p00, p10, p11) + triangleSolidAngle(p00, p11, p01);
}

describe('rectangle light sampler', () => {
  const session = useRenderSession();
  const cases: [string, V, boolean][] = [
    ['near, below its centre', [0.2, 0.7, 0.1], true],
    ['grazing, off its side', [1.2, 0.9, -0.2], true],
    ['far away (by area)', [3, -30, 2], false],
  ];
  for (const [name, x, bySolidAngle] of cases) {
    it(`draws points with the density it reports: ${name}`, async () => {
      const omega = solidAngle(x);
      expect(omega > MIN_SOLID_ANGLE && omega < MAX_SOLID_ANGLE).toBe(bySolidAngle);
      const data = await session().runKernel({ kernel: 'sampleRectangle', width: SIDE, height: SIDE, wo: x, rect: [...c, ...u, ...v], seed: 7 });
      const n = SIDE * SIDE;
      const observed = new Float64Array(CELLS * CELLS);
      let worstPdf = 0;
      let worstLookup = 0;
      let inverseSum = 0;
      for (let i = 0; i < n; i++) {
        const [a, b, pdf, lookup] = data.subarray(i * 4, i * 4 + 4);
        expect(Math.abs(a) <= 1 + 1e-4 && Math.abs(b) <= 1 + 1e-4, `sample ${i} at (${a}, ${b})`).toBe(true);
        const p = at(a, b);
        const d = sub(p, x);
        const areaPdf = dot(d, d) / ((Math.abs(dot(d, [0, -1, 0])) / len(d)) * 4 * len(u) * len(v));
        worstPdf = Math.max(worstPdf, Math.abs(pdf * (bySolidAngle ? omega : 1 / areaPdf) - 1));
        worstLookup = Math.max(worstLookup, Math.abs(lookup / pdf - 1));
        inverseSum += 1 / pdf;
        const cell = (k: number) => Math.min(CELLS - 1, Math.max(0, Math.floor(((k + 1) / 2) * CELLS)));
        observed[cell(a) * CELLS + cell(b)]++;
      }
      const expected = new Float64Array(CELLS * CELLS);
      const edge = (k: number) => -1 + (2 * k) / CELLS;
      for (let i = 0; i < CELLS; i++) {
        for (let j = 0; j < CELLS; j++) {
          const share = bySolidAngle ? solidAngle(x, edge(i), edge(i + 1), edge(j), edge(j + 1)) / omega : 1 / (CELLS * CELLS);
          expected[i * CELLS + j] = n * share;
        }
      }
      expect(worstPdf, 'reported density against the exact one').toBeLessThan(2e-3);
      expect(worstLookup, 'rectanglePdf of the point against the sampler').toBeLessThan(2e-3);
      expect(inverseSum / n / omega - 1, 'mean of 1 / pdf against the solid angle').toBeCloseTo(0, 2);
      const result = chiSquareTest(observed, expected);
      expect(result.pValue, JSON.stringify(result)).toBeGreaterThan(ALPHA);
    });
  }
});
