/**
 * Start-up timestamps for measuring the CLI: with PATHTRACE_TIMING set, each
 * mark() writes `timing: <ms since the process started> <label>` to stderr.
 * Without it, mark() does nothing.
 */
const enabled = typeof process !== 'undefined' && !!process.env.PATHTRACE_TIMING;

export function mark(label: string): void {
  if (enabled) process.stderr.write(`timing: ${performance.now().toFixed(0)} ${label}\n`);
}
