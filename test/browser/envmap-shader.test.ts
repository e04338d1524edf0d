/**
 * The environment map's GLSL in the browser (src/shaders/lights/
 * environment_map.glsl through src/headless/environmentKernels.ts):
 * sampleEnvironment against environmentPdf (chi-square), environmentPdf's
 * normalization over the sphere, the orientation against the scene format's
 * mapping formula, and environmentRadiance against a TypeScript bilinear
 * reference.
 */
import { describe, expect, it } from 'vitest';
import { chiSquareTest } from '../support/chi2';
import { useRenderSession } from '../support/browser';
import type { RenderSession } from '../../src/node/session';
import type { EnvironmentKernelRequest } from '../../src/headless/environmentKernels';
import type { EnvironmentImage } from '../../src/scene/types';
import { directionToUv, lookupEnvironment } from '../../src/scene/envmap/mapping';
import { buildEnvironmentDistribution, environmentDistributionPdf } from '../../src/scene/envmap/distribution';

const ALPHA = 1e-4;

async function runKernel(session: RenderSession, request: EnvironmentKernelRequest): Promise<Float32Array> {
  const base64 = await session.page.evaluate((r) => window.pathtraceEnvironmentKernels.run(r), request);
  const bytes = Buffer.from(base64, 'base64');
  return new Float32Array(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength));
}

function makeMap(width: number, height: number, f: (x: number, y: number) => number): EnvironmentImage {
  const rgb = new Float32Array(width * height * 3);
  for (let y = 0; y < height; y++) for (let x = 0; x < width; x++) rgb.set([f(x, y), f(x, y) * 0.7, f(x, y) * 0.4], (y * width + x) * 3);
  return { width, height, rgb };
}

const asRequestMap = (m: EnvironmentImage) => ({ width: m.width, height: m.height, rgb: Array.from(m.rgb) });

/** The scene format's mapping, written out here (not taken from the code under test). */
function formatUv(d: number[], rotationDegrees: number): { u: number; v: number } {
  const a = (-rotationDegrees * Math.PI) / 180; // undo to_world = rotation about +y
  const x = Math.cos(a) * d[0] + Math.sin(a) * d[2];
  const z = -Math.sin(a) * d[0] + Math.cos(a) * d[2];
  const u = 0.5 + Math.atan2(-x, z) / (2 * Math.PI);
  return { u: u - Math.floor(u), v: Math.acos(d[1]) / Math.PI };
}

// 64 x 33: 64 x 32 cells of the distribution.
const W = 64;
const H = 33;
const MAPS: [string, EnvironmentImage, number][] = [
  ['tiny bright spot', makeMap(W, H, (x, y) => (x === 40 && y === 9 ? 1000 : 0.05)), 0],
  ['smooth', makeMap(W, H, (x, y) => 1 + 3 * Math.sin((x / W) * 2 * Math.PI) ** 2 + y / 8), 37],
];

describe('environment map shader', () => {
  const session = useRenderSession();

  for (const [name, map, rotation] of MAPS) {
    it(`sampleEnvironment draws from environmentPdf: ${name}, rotation ${rotation}`, async () => {
      const side = 512; // 262,144 samples
      const samples = await runKernel(session(), { kernel: 'sample', width: side, height: side, map: asRequestMap(map), rotation, intensity: 1, seed: 9 });
      // Bins of 2 x 2 cells in (u, v); cells start half a column right of u = 0.
      const bins = { u: W / 2, v: (H - 1) / 2 };
      const binOf = (u: number, v: number) => {
        const shifted = u - 0.5 / W;
        const bu = Math.min(Math.floor((shifted - Math.floor(shifted)) * bins.u), bins.u - 1);
        return Math.min(Math.floor(v * bins.v), bins.v - 1) * bins.u + bu;
      };
      const observed = new Float64Array(bins.u * bins.v);
      const n = side * side;
      let badNorm = 0;
      for (let i = 0; i < n; i++) {
        const [x, y, z, pdf] = samples.subarray(i * 4, i * 4 + 4);
        if (!(pdf > 0) || Math.abs(Math.hypot(x, y, z) - 1) > 1e-3) badNorm++;
        const { u, v } = formatUv([x, y, z], rotation);
        observed[binOf(u, v)]++;
      }
      expect(badNorm, 'samples with a zero pdf or not unit length').toBe(0);

      // environmentPdf on a grid of directions at (u, v) sub-cell centres,
      // turned into a density on (u, v) by the Jacobian 2 pi^2 sin(theta).
      const sub = 4;
      const grid = { u: W * sub, v: (H - 1) * sub };
      const pdfs = await runKernel(session(), {
        kernel: 'pdfUvGrid', width: grid.u, height: grid.v, map: asRequestMap(map), rotation, intensity: 1, params: [0.5 / W, 0, 0, 0],
      });
      const expected = new Float64Array(bins.u * bins.v);
      let mass = 0;
      for (let py = 0; py < grid.v; py++) {
        for (let px = 0; px < grid.u; px++) {
          const [x, y, z, pdf] = pdfs.subarray((py * grid.u + px) * 4, (py * grid.u + px) * 4 + 4);
          const { u, v } = formatUv([x, y, z], rotation);
          const cellMass = (pdf * 2 * Math.PI * Math.PI * Math.sin(Math.PI * v)) / (grid.u * grid.v);
          mass += cellMass;
          expected[binOf(u, v)] += cellMass * n;
        }
      }
      expect(Math.abs(mass - 1)).toBeLessThan(1e-3);
      const result = chiSquareTest(observed, expected);
      expect(result.degreesOfFreedom).toBeGreaterThan(400);
      expect(result.pValue, JSON.stringify(result)).toBeGreaterThan(ALPHA);
    });
  }

  it('environmentPdf integrates to 1 over the sphere (solid-angle Jacobian), spot and smooth maps', async () => {
    for (const [, map, rotation] of MAPS) {
      const grid = { u: 1024, v: 512 }; // uniform in (cos theta, phi): dA = 4 pi / N
      const pdfs = await runKernel(session(), { kernel: 'pdfSphereGrid', width: grid.u, height: grid.v, map: asRequestMap(map), rotation, intensity: 1 });
      let sum = 0;
      for (let i = 0; i < grid.u * grid.v; i++) sum += pdfs[i * 4 + 3];
      expect(Math.abs((sum * 4 * Math.PI) / (grid.u * grid.v) - 1)).toBeLessThan(0.01);
    }
  });

  // A map black but for a block of texels around u = 0.75, v = 0.5 (centres
  // of columns 46..49 lie at u = 0.727..0.773, rows 15..17 at v = 0.47..0.53).
  const block = makeMap(W, H, (x, y) => (x >= 46 && x <= 49 && y >= 15 && y <= 17 ? 10 : 0));
  const inBlockInterior = (u: number, v: number) => u >= 46.5 / W && u <= 48.5 / W && v >= 15 / (H - 1) && v <= 17 / (H - 1);
  const radianceAt = async (d: number[], rotation: number, intensity = 1) =>
    (await runKernel(session(), { kernel: 'radianceAt', width: 1, height: 1, map: asRequestMap(block), rotation, intensity, params: d }))[0];

  it('orientation: the block at u = 0.75 is seen from -x; rotation 90 turns it to +z, as the format (and Mitsuba) map it', async () => {
    const axes = [[1, 0, 0], [-1, 0, 0], [0, 0, 1], [0, 0, -1], [0, 1, 0], [0, -1, 0]];
    for (const rotation of [0, 90, -90, 180]) {
      for (const d of axes) {
        const { u, v } = formatUv(d, rotation);
        const expected = inBlockInterior(u, v) ? 10 : 0;
        expect(await radianceAt(d, rotation), `direction ${d}, rotation ${rotation}`).toBeCloseTo(expected, 4);
      }
    }
    // The facts themselves, checked with Mitsuba 3.9's envmap (to_world = rotate([0, 1, 0], angle)):
    expect(await radianceAt([-1, 0, 0], 0)).toBeCloseTo(10, 4);
    expect(await radianceAt([0, 0, 1], 90)).toBeCloseTo(10, 4);
    expect(await radianceAt([-1, 0, 0], 90)).toBe(0);
    expect(await radianceAt([-1, 0, 0], 0, 2.5)).toBeCloseTo(25, 3);
  });

  it('environmentRadiance is the bilinear lookup of the format at random directions', async () => {
    let state = 12345;
    const rand = () => ((state = (state * 1103515245 + 12345) % 2147483648) / 2147483648);
    const map = makeMap(37, 19, () => rand());
    const rotation = 123;
    const intensity = 1.7;
    const side = 64;
    const request = { width: side, height: side, map: asRequestMap(map), rotation, intensity, seed: 4 };
    const directions = await runKernel(session(), { ...request, kernel: 'randomDirection' });
    const radiance = await runKernel(session(), { ...request, kernel: 'randomRadiance' });
    let worst = 0;
    for (let i = 0; i < side * side; i++) {
      const d = Array.from(directions.subarray(i * 4, i * 4 + 3)) as [number, number, number];
      const { u, v } = directionToUv(d, rotation);
      const reference = lookupEnvironment(map, u, v).map((c) => c * intensity);
      for (let c = 0; c < 3; c++) worst = Math.max(worst, Math.abs(radiance[i * 4 + c] - reference[c]));
    }
    // Texels in [0, 1) over 37 columns: a direction error of 1e-4 rad (SwiftShader's atan/acos) moves the value by < 1e-3.
    expect(worst).toBeLessThan(2e-3);
  });

  it('the pdf returned with each sample is environmentPdf of its direction, and the TypeScript reference pdf', async () => {
    for (const [, map, rotation] of MAPS) {
      const side = 128;
      const request = { width: side, height: side, map: asRequestMap(map), rotation, intensity: 1, seed: 21 };
      const pdfPairs = await runKernel(session(), { ...request, kernel: 'samplePdfs' });
      const samples = await runKernel(session(), { ...request, kernel: 'sample' });
      const distribution = buildEnvironmentDistribution(map);
      let shaderMismatches = 0;
      let referenceMismatches = 0;
      for (let i = 0; i < side * side; i++) {
        if (Math.abs(pdfPairs[i * 4] / pdfPairs[i * 4 + 1] - 1) > 1e-4) shaderMismatches++;
        const [x, y, z, pdf] = samples.subarray(i * 4, i * 4 + 4);
        const { u, v } = formatUv([x, y, z], rotation);
        if (Math.abs(pdf / environmentDistributionPdf(distribution, u, v) - 1) > 1e-2) referenceMismatches++;
      }
      // A direction within float rounding of a cell edge may land in the
      // neighbour cell (SwiftShader's trigonometry is good to ~1e-4).
      expect(shaderMismatches / (side * side)).toBeLessThan(5e-3); // measured: 0.13 %
      expect(referenceMismatches / (side * side)).toBeLessThan(5e-3);
    }
  });
});
