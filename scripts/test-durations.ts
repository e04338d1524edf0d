/**
 * Rewrites test/durations.json (the seconds each test file took, which
 * test/support/sequencer.ts orders the files by) from the JSON report that
 * `npm test` writes to test-output/vitest-report.json. Run it after a full
 * run on a quiet machine: `npm run test:durations`.
 */
import { readFileSync, writeFileSync } from 'node:fs';
import { relative, resolve } from 'node:path';

interface Report {
  testResults: { name: string; startTime: number; endTime: number }[];
}

const root = resolve(import.meta.dirname, '..');
const reportPath = resolve(root, process.argv[2] ?? 'test-output/vitest-report.json');
const report = JSON.parse(readFileSync(reportPath, 'utf8')) as Report;
const durations: Record<string, number> = {};
const results = [...report.testResults].sort((a, b) => b.endTime - b.startTime - (a.endTime - a.startTime));
// Paths from the project root, whichever checkout the report came from (CI runs a fresh clone).
const fromRoot = (file: string) => /(?:^|\/)((?:test|src)\/.*)$/.exec(relative(root, file))?.[1] ?? relative(root, file);
for (const file of results) durations[fromRoot(file.name)] = Math.round((file.endTime - file.startTime) / 100) / 10;
writeFileSync(resolve(root, 'test/durations.json'), `${JSON.stringify(durations, null, 2)}\n`);
console.log(`test/durations.json: ${results.length} files, ${Object.values(durations).reduce((a, b) => a + b, 0).toFixed(0)} s in all`);
