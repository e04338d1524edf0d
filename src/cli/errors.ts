/**
 * Errors the command line reports, and how they become exit codes and lines.
 *
 * Exit codes: 0 success; 2 bad arguments, unreadable or invalid scene, bad
 * output path; 1 a rendering failure (Chromium missing, WebGL error, ...);
 * 130 interrupted.
 * Every failure prints one line per problem and never a stack trace, unless
 * PATHTRACE_DEBUG=1 is set.
 */

export const EXIT_OK = 0;
export const EXIT_FAILURE = 1;
export const EXIT_USAGE = 2;
/** Ctrl-C / SIGTERM during a render (128 + SIGINT, as shells report it). */
export const EXIT_INTERRUPTED = 130;

export type ExitCode = typeof EXIT_OK | typeof EXIT_FAILURE | typeof EXIT_USAGE | typeof EXIT_INTERRUPTED;

/** An error meant for the user: `lines` are printed as they are, one per problem. */
export class CliError extends Error {
  readonly exitCode: ExitCode;
  readonly lines: string[];

  constructor(exitCode: ExitCode, lines: string | string[], options?: { cause?: unknown }) {
    const all = (Array.isArray(lines) ? lines : [lines]).map(oneLine);
    super(all.join('\n'), options);
    this.name = 'CliError';
    this.exitCode = exitCode;
    this.lines = all;
  }
}

/** A bad flag, argument, scene or output path: exit 2. */
export function usageError(lines: string | string[], cause?: unknown): CliError {
  return new CliError(EXIT_USAGE, lines, { cause });
}

/** Something failed while rendering or writing: exit 1. */
export function failure(lines: string | string[], cause?: unknown): CliError {
  return new CliError(EXIT_FAILURE, lines, { cause });
}

/** Collapses whitespace and newlines so a message always fits on one line. */
export function oneLine(text: string): string {
  return text.replace(/\s*[\r\n]+\s*/g, ' ').trim();
}

/** The first line of an arbitrary thrown value's message (Playwright messages run to many lines). */
export function firstLine(error: unknown): string {
  const message = error instanceof Error ? error.message : String(error);
  const line = message.split(/\r?\n/).find((l) => l.trim() !== '') ?? '';
  return line.trim() || (error instanceof Error ? error.name : 'unknown error');
}

export function debugEnabled(env: NodeJS.ProcessEnv = process.env): boolean {
  return env.PATHTRACE_DEBUG === '1';
}

/**
 * What to print for any thrown value, and the exit code. A CliError prints its
 * lines; anything else is an unexpected failure: exit 1, `error: <first line>`.
 */
export function describeError(error: unknown, env: NodeJS.ProcessEnv = process.env): { exitCode: ExitCode; lines: string[] } {
  const lines = error instanceof CliError ? [...error.lines] : [`error: ${firstLine(error)}`];
  const exitCode = error instanceof CliError ? error.exitCode : EXIT_FAILURE;
  if (debugEnabled(env)) lines.push(...debugDetails(error));
  return { exitCode, lines };
}

function debugDetails(error: unknown): string[] {
  const out: string[] = [];
  let current: unknown = error;
  for (let depth = 0; current !== undefined && depth < 5; depth++) {
    if (current instanceof Error) out.push(current.stack ?? `${current.name}: ${current.message}`);
    else out.push(String(current));
    current = current instanceof Error ? current.cause : undefined;
    if (current !== undefined) out.push('caused by:');
  }
  return out;
}
