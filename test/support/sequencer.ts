/**
 * The order the test files start in: longest first (the LPT rule), so that
 * the two workers finish together instead of one running a long reference
 * file alone at the end. Vitest's own sequencer orders by the durations in
 * its cache, which a fresh clone (CI) does not have: there it ran the files
 * in glob order. So the durations measured last are committed in
 * test/durations.json (`npm run test:durations` rewrites it from a run's
 * report); a file not in it counts as the median.
 */
import { readFileSync } from 'node:fs';
import { relative } from 'node:path';
import { BaseSequencer, type TestSpecification } from 'vitest/node';

type Durations = Record<string, number>;

function loadDurations(): Durations {
  try {
    return JSON.parse(readFileSync(new URL('../durations.json', import.meta.url), 'utf8')) as Durations;
  } catch {
    return {};
  }
}

function median(values: number[]): number {
  const sorted = [...values].sort((a, b) => a - b);
  return sorted.length ? sorted[Math.floor(sorted.length / 2)] : 0;
}

export class LongestFirstSequencer extends BaseSequencer {
  override async sort(files: TestSpecification[]): Promise<TestSpecification[]> {
    const durations = loadDurations();
    const unknown = median(Object.values(durations));
    const root = this.ctx.config.root;
    const seconds = (file: TestSpecification): number => durations[relative(root, file.moduleId)] ?? unknown;
    return [...files].sort((a, b) => {
      const group = a.project.config.sequence.groupOrder - b.project.config.sequence.groupOrder;
      if (group !== 0) return group;
      if (a.project.name !== b.project.name) return a.project.name < b.project.name ? -1 : 1;
      return seconds(b) - seconds(a);
    });
  }
}
