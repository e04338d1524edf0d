/**
 * The render loop's paths per frame (src/app/pathBudget.ts), against a
 * simulated GPU whose measurements arrive a few frames late and are noisy:
 * it settles where a frame's work fits the target, without oscillating; it
 * starts small after a restart and grows only from measurements of the new
 * scene; frames stalled now and then (a loaded machine) move nothing; a
 * heavier view is followed within a few measurements.
 */
import { describe, expect, it } from 'vitest';
import { GROWTH, PathBudget, type PathBudgetOptions } from '../../src/app/pathBudget';
import { random } from '../support/random';

const OPTIONS: PathBudgetOptions = { targetMs: 30, startPaths: 1024, minPaths: 256, maxPaths: 512 * 196_608 };

/**
 * Runs `frames` frames: each traces budget.paths paths costing `cost(frame)`
 * ms each (times a noise factor), measured `lag` frames later. Returns the
 * paths of every frame and the ms of work each took.
 */
function simulate(budget: PathBudget, frames: number, cost: (frame: number) => number, lag = 3, noise = 0.2, seed = 1) {
  const rand = random(seed);
  const pending: { ms: number; paths: number; at: number }[] = [];
  const paths: number[] = [];
  const work: number[] = [];
  for (let f = 0; f < frames; f++) {
    while (pending.length && pending[0].at <= f) {
      const m = pending.shift()!;
      budget.observe(m.ms, m.paths);
    }
    const p = budget.paths;
    const ms = p * cost(f) * (1 + noise * (2 * rand() - 1));
    paths.push(p);
    work.push(ms);
    pending.push({ ms, paths: p, at: f + lag });
  }
  return { paths, work };
}

describe('PathBudget', () => {
  it('settles where a frame fits the target, and stays there', () => {
    for (const msPerPath of [2e-4, 1.5e-3, 2.5e-2]) {
      const budget = new PathBudget(OPTIONS);
      const { paths, work } = simulate(budget, 200, () => msPerPath);
      const settled = paths.slice(100);
      const ideal = OPTIONS.targetMs / msPerPath;
      // Within the noise of the measurements, a little below the ideal (the median of 3 of noisy ones).
      for (const p of settled) {
        expect(p).toBeGreaterThan(0.7 * ideal);
        expect(p).toBeLessThan(1.2 * ideal);
      }
      // No oscillation: frame to frame, the paths change by a few percent at most.
      for (let i = 1; i < settled.length; i++) expect(Math.abs(settled[i] / settled[i - 1] - 1)).toBeLessThan(0.15);
      expect(Math.max(...work.slice(100))).toBeLessThan(1.5 * OPTIONS.targetMs);
    }
  });

  it('starts small after a restart and grows only from what it measured', () => {
    const budget = new PathBudget(OPTIONS);
    simulate(budget, 100, () => 1e-3);
    expect(budget.paths).toBeGreaterThan(20_000);
    budget.restart(); // a 1M-triangle mesh was added: 25 us per path
    expect(budget.paths).toBe(OPTIONS.startPaths);
    const { paths, work } = simulate(budget, 60, () => 2.5e-2);
    // No frame much above the target on the way (the first are at startPaths, 26 ms).
    expect(Math.max(...work)).toBeLessThan(1.5 * OPTIONS.targetMs);
    for (let i = 1; i < paths.length; i++) expect(paths[i]).toBeLessThanOrEqual(Math.max(paths[i - 1], paths[Math.max(0, i - 3)] * GROWTH) + 1e-9);
    expect(paths[paths.length - 1]).toBeGreaterThan(0.7 * (30 / 2.5e-2));
  });

  it('grows by at most GROWTH times the measured frame, however late the measurements', () => {
    const budget = new PathBudget(OPTIONS);
    // A cheap scene measured 8 frames late: without the bound, the 8 measurements of
    // 1024-path frames that arrive before the first larger frame is measured would compound.
    // (The first 2 measurements make no estimate yet: they may hold a compile.)
    const { paths } = simulate(budget, 18, () => 1e-5, 8, 0);
    expect(paths.slice(0, 10)).toEqual(new Array(10).fill(OPTIONS.startPaths));
    expect(paths.slice(10)).toEqual(new Array(8).fill(OPTIONS.startPaths * GROWTH));
  });

  it('ignores two stalled frames of five, follows three', () => {
    const budget = new PathBudget(OPTIONS);
    simulate(budget, 100, () => 1e-3, 3, 0);
    const settled = budget.paths;
    // Frames 10x as long now and then: the machine, not the scene.
    for (const cost of [1e-2, 1e-3, 1e-3, 1e-2, 1e-3, 1e-3, 1e-2, 1e-3]) {
      budget.observe(settled * cost, settled);
      expect(budget.paths).toBeCloseTo(settled, 6);
    }
    for (let i = 0; i < 5; i++) budget.observe(settled * 1e-3, settled);
    // The view got 5x heavier: followed at the third measurement.
    budget.observe(settled * 5e-3, settled);
    budget.observe(settled * 5e-3, settled);
    expect(budget.paths).toBeCloseTo(settled, 6);
    budget.observe(settled * 5e-3, settled);
    expect(budget.paths).toBeCloseTo(OPTIONS.targetMs / 5e-3, 6);
  });

  it('is not misled by a first frame that compiled the program', () => {
    const budget = new PathBudget(OPTIONS);
    budget.observe(800, OPTIONS.startPaths); // 800 ms: SwiftShader compiled at the first draw
    budget.observe(OPTIONS.startPaths * 1e-3, OPTIONS.startPaths);
    expect(budget.paths).toBe(OPTIONS.startPaths);
    budget.observe(OPTIONS.startPaths * 1e-3, OPTIONS.startPaths);
    expect(budget.paths).toBe(OPTIONS.startPaths * GROWTH);
  });

  it('grows by frame gaps until the first estimate: fast for a cheap scene, not at all for a heavy one', () => {
    const cheap = new PathBudget(OPTIONS);
    for (let f = 0; f < 6; f++) cheap.observeGap(17, cheap.paths);
    expect(cheap.paths).toBe(OPTIONS.startPaths * 64);
    const heavy = new PathBudget(OPTIONS);
    for (let f = 0; f < 6; f++) heavy.observeGap(33, heavy.paths);
    expect(heavy.paths).toBe(OPTIONS.startPaths);
    // Once the timer's measurements make an estimate, gaps no longer count.
    for (let i = 0; i < 3; i++) cheap.observe(30, cheap.paths);
    const estimated = cheap.paths;
    cheap.observeGap(1, cheap.paths);
    expect(cheap.paths).toBe(estimated);
  });

  it('stays within its bounds', () => {
    const budget = new PathBudget(OPTIONS);
    simulate(budget, 50, () => 10, 1, 0); // 10 ms per path
    expect(budget.paths).toBe(OPTIONS.minPaths);
    budget.setOptions({ ...OPTIONS, maxPaths: 5000 });
    simulate(budget, 100, () => 1e-7, 1, 0);
    expect(budget.paths).toBe(5000);
  });
});
