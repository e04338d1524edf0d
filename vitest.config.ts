import { availableParallelism } from 'node:os';
import { configDefaults, defineConfig } from 'vitest/config';
import { LongestFirstSequencer } from './test/support/sequencer';

/**
 * Browser test files whose checks measure time on the wall or page clock
 * (frame gaps, a freeze, the first pixel, a denoise's main-thread gap, a
 * child's exit within seconds) or that must finish a cold compile within a
 * short per-test timeout. They run one at a time after the rest, with the
 * machine to themselves, so that what they measure is the renderer, not a
 * neighbour. A new test that times something belongs here.
 */
const TIMED = [
  'test/browser/first-pixel.test.ts',
  'test/browser/denoise.test.ts',
  'test/browser/context-loss.test.ts',
  'test/browser/cli-robustness.test.ts',
  'test/browser/page-denoise.test.ts',
  'test/browser/page-envmap.test.ts',
  'test/browser/page-heavy-mesh.test.ts',
  'test/browser/page-materials.test.ts',
];

const INCLUDE = ['test/**/*.test.ts', 'src/**/*.test.ts'];

/**
 * Most of the browser tests' time is SwiftShader compiling a program, on one
 * thread of Chromium's GPU process (measured: one thread busy, the others
 * idle), and a program compiled in one WebGL context is compiled again in
 * the next, even in the same browser (ANGLE's disk cache keeps the
 * translated shader, not SwiftShader's machine code: no gain measured with a
 * shared profile). So the other files run PARALLEL at a time, each with its
 * own Chromium (one browser would serialize their compiles on its GPU
 * process's one thread): one per core (two on this 2-core machine), at most
 * four (each Chromium takes up to ~3 GB compiling). PATHTRACE_TEST_WORKERS
 * overrides (1 runs every file one at a time, as before: on a machine that
 * others are using too, their processes take the second core anyway).
 */
const PARALLEL = Number(process.env.PATHTRACE_TEST_WORKERS) || Math.min(4, availableParallelism());

const shared = {
  testTimeout: 300_000,
  hookTimeout: 120_000,
};

export default defineConfig({
  test: {
    sequence: { sequencer: LongestFirstSequencer },
    projects: [
      {
        test: {
          ...shared,
          name: 'parallel',
          include: INCLUDE,
          exclude: [...configDefaults.exclude, ...TIMED],
          maxWorkers: PARALLEL,
          sequence: { groupOrder: 0 },
        },
      },
      {
        test: {
          ...shared,
          name: 'timed',
          include: TIMED,
          fileParallelism: false,
          sequence: { groupOrder: 1 },
        },
      },
    ],
  },
});
