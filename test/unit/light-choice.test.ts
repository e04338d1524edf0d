/**
 * The emitter choice by where the shading point is (src/render/lightChoice.ts):
 * no emitter is given probability 0 in a cell holding a point it lights
 * (that would lose light: next-event estimation is the only way to delta
 * lights), every table is a distribution that its alias entries draw
 * exactly, and points outside the grid use the global table.
 */
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { buildAliasTable } from '../../src/render/aliasTable';
import { buildLightChoice, cellProbabilities, gridCells, reachWeight, tableAt, UNIFORM_SHARE, type Box } from '../../src/render/lightChoice';
import type { LightReach } from '../../src/lights/kind';
import type { Vec3 } from '../../src/scene/types';

const vec = fc.tuple(fc.double({ min: -5, max: 5, noNaN: true }), fc.double({ min: -5, max: 5, noNaN: true }), fc.double({ min: -5, max: 5, noNaN: true }));
const unit = vec.filter((v) => Math.hypot(...v) > 1e-3).map((v) => v.map((c) => c / Math.hypot(...v)) as Vec3);
const sub = (a: Vec3, b: Vec3): Vec3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a: Vec3, b: Vec3) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];

/** Does the emitter send light to point x at all (what must never get probability 0)? */
function lights(reach: LightReach, x: Vec3): boolean {
  if (!reach.bound) return reach.strength > 0;
  const toX = sub(x, reach.bound.center);
  if (reach.front && dot(toX, reach.front) <= 0) return false;
  if (reach.cone) {
    const d = Math.hypot(...toX);
    if (d > 0 && dot(toX, reach.cone.axis) / d < reach.cone.cosCutoff) return false;
  }
  return reach.strength > 0;
}

const reachArb: fc.Arbitrary<LightReach> = fc.oneof(
  fc.record({ center: vec, radius: fc.double({ min: 0, max: 1, noNaN: true }) }).map(({ center, radius }) => ({ bound: { center, radius }, strength: 1 })),
  fc.record({ center: vec, front: unit, radius: fc.double({ min: 0.01, max: 1, noNaN: true }) }).map(({ center, front, radius }) => ({ bound: { center, radius }, strength: 2, front })),
  fc.record({ center: vec, axis: unit, cutoff: fc.double({ min: 1, max: 90, noNaN: true }) }).map(({ center, axis, cutoff }) => ({
    bound: { center, radius: 0 },
    strength: 3,
    cone: { axis, cosCutoff: Math.cos((cutoff * Math.PI) / 180) },
  })),
  fc.constant<LightReach>({ bound: null, strength: 0.5 }),
);

describe('reachWeight', () => {
  it('is positive for a cell whenever the emitter lights some point of it (random emitters, cells and points)', () => {
    fc.assert(
      fc.property(reachArb, vec, fc.double({ min: 0.01, max: 2, noNaN: true }), fc.array(fc.tuple(fc.double({ min: -1, max: 1, noNaN: true }), fc.double({ min: -1, max: 1, noNaN: true }), fc.double({ min: -1, max: 1, noNaN: true })), { minLength: 1, maxLength: 20 }), (reach, center, half, offsets) => {
        // Points of the cube of half-size `half` around `center`; the ball has radius half * sqrt(3).
        const lit = offsets.some((o) => lights(reach, [center[0] + o[0] * half, center[1] + o[1] * half, center[2] + o[2] * half]));
        if (lit) expect(reachWeight(reach, center, half * Math.sqrt(3))).toBeGreaterThan(0);
      }),
      { numRuns: 3000 },
    );
  });

  it('is 0 for a cell wholly behind a one-sided light or outside a spot\'s cone', () => {
    const panel: LightReach = { bound: { center: [0, 2, 0], radius: 0.5 }, strength: 1, front: [0, -1, 0] };
    expect(reachWeight(panel, [0, 3, 0], 0.5)).toBe(0);
    expect(reachWeight(panel, [0, 1, 0], 0.5)).toBeGreaterThan(0);
    const spot: LightReach = { bound: { center: [0, 3, 0], radius: 0 }, strength: 1, cone: { axis: [0, -1, 0], cosCutoff: Math.cos(Math.PI / 12) } };
    expect(reachWeight(spot, [3, 0, 0], 0.2)).toBe(0);
    expect(reachWeight(spot, [0.5, 0, 0], 0.2)).toBeGreaterThan(0);
    // A cell whose centre is outside the cone but whose corner is inside it.
    const narrow: LightReach = { bound: { center: [0, 0, 0], radius: 0 }, strength: 1, cone: { axis: [0, -1, 0], cosCutoff: Math.cos(Math.PI / 12) } };
    expect(lights(narrow, [0.4, -2, 0])).toBe(true);
    expect(reachWeight(narrow, [1.2, -2, 0], 0.8 * Math.sqrt(3))).toBeGreaterThan(0);
    // Falls as 1 / d^2 away from a point light.
    const point: LightReach = { bound: { center: [0, 0, 0], radius: 0 }, strength: 1 };
    expect(reachWeight(point, [4, 0, 0], 0.1) / reachWeight(point, [2, 0, 0], 0.1)).toBeCloseTo(0.25, 10);
  });
});

describe('cellProbabilities', () => {
  it('mixes the weights with a uniform choice among the emitters that light the cell, and falls back to the global table when none does', () => {
    const p = cellProbabilities([3, 1, 0], [0.2, 0.3, 0.5]);
    expect(p[2]).toBe(0);
    expect(p[0]).toBeCloseTo((1 - UNIFORM_SHARE) * 0.75 + UNIFORM_SHARE / 2, 12);
    expect(p.reduce((a, b) => a + b, 0)).toBeCloseTo(1, 12);
    expect(cellProbabilities([0, 0, 0], [0.2, 0.3, 0.5])).toEqual([0.2, 0.3, 0.5]);
  });
});

describe('buildLightChoice', () => {
  const box: Box = { min: [-2, 0, -3], max: [2, 3, 3] };
  const reaches: LightReach[] = [
    { bound: { center: [-1, 2.5, 0], radius: 0.4 }, strength: 2, front: [0, -1, 0] },
    { bound: { center: [1, 2.8, -1], radius: 0 }, strength: 5, cone: { axis: [0, -1, 0], cosCutoff: Math.cos(0.4) } },
    { bound: null, strength: 0.3 },
  ];
  const globalWeights = [0.5, 0.3, 0.2];
  const choice = buildLightChoice(reaches, globalWeights, box);
  const count = reaches.length;
  const entry = (table: number, i: number) => choice.texels.subarray((table * count + i) * 4, (table * count + i) * 4 + 4);

  it('has a distribution per table that its alias entries draw exactly', () => {
    expect(choice.tables).toBe(choice.cells[0] * choice.cells[1] * choice.cells[2] + 1);
    for (let t = 0; t < choice.tables; t++) {
      const drawn = new Array<number>(count).fill(0);
      let total = 0;
      for (let i = 0; i < count; i++) {
        const [threshold, alias, pdf, aliasPdf] = entry(t, i);
        total += pdf;
        drawn[i] += threshold / count;
        drawn[alias] += (1 - threshold) / count;
        expect(aliasPdf).toBe(entry(t, alias)[2]);
      }
      expect(total).toBeCloseTo(1, 5);
      for (let i = 0; i < count; i++) expect(drawn[i]).toBeCloseTo(entry(t, i)[2], 5);
    }
  });

  it("gives each cell the probabilities cellProbabilities makes of its reach weights", () => {
    const size = [0, 1, 2].map((k) => (box.max[k] - box.min[k]) / choice.cells[k]);
    const radius = Math.hypot(...size) / 2;
    for (const [x, y, z] of [[0, 0, 0], [3, 5, 7], [choice.cells[0] - 1, choice.cells[1] - 1, choice.cells[2] - 1]]) {
      const center: Vec3 = [box.min[0] + (x + 0.5) * size[0], box.min[1] + (y + 0.5) * size[1], box.min[2] + (z + 0.5) * size[2]];
      const expected = cellProbabilities(reaches.map((r) => reachWeight(r, center, radius)), globalWeights);
      const table = tableAt(choice, center);
      expected.forEach((p, i) => expect(entry(table, i)[2]).toBeCloseTo(p, 6));
    }
  });

  it('uses, outside the grid, the global table of the choice by power', () => {
    const global = buildAliasTable(globalWeights);
    for (let i = 0; i < count; i++) expect(Array.from(entry(choice.tables - 1, i))).toEqual(Array.from(new Float32Array([global.threshold[i], global.alias[i], global.pdf[i], global.pdf[global.alias[i]]])));
    expect(tableAt(choice, [0, -1, 0])).toBe(choice.tables - 1);
    expect(tableAt(choice, [0, 1, 10])).toBe(choice.tables - 1);
  });

  it('gives the spot probability 0 where its cone cannot reach, and some where it lands', () => {
    expect(entry(tableAt(choice, [1, 0.1, -1]), 1)[2]).toBeGreaterThan(0.2);
    expect(entry(tableAt(choice, [-1.9, 0.1, 2.9]), 1)[2]).toBe(0);
    // Above the panel (it faces down): no choice of it there.
    expect(entry(tableAt(choice, [-1, 2.95, 0]), 0)[2]).toBe(0);
  });

  it('makes no grid for one emitter, or for emitters that are all at infinity', () => {
    expect(buildLightChoice([reaches[0]], [1], box).tables).toBe(1);
    expect(buildLightChoice([reaches[2], reaches[2]], [1, 1], box).tables).toBe(1);
    expect(buildLightChoice(reaches, globalWeights, null).tables).toBe(1);
  });

  it('sizes the grid by the box, within the budget', () => {
    const cells = gridCells({ min: [0, 0, 0], max: [10, 1, 10] }, 4096);
    expect(cells[0]).toBe(cells[2]);
    expect(cells[1]).toBeLessThan(cells[0]);
    expect(cells[0] * cells[1] * cells[2]).toBeLessThanOrEqual(4096);
    const small = gridCells({ min: [0, 0, 0], max: [1, 1, 1] }, 100);
    expect(small[0] * small[1] * small[2]).toBeLessThanOrEqual(100);
  });
});
