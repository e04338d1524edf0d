/**
 * src/cli/compileCache.ts in child processes (the cache is written at exit):
 * a big CommonJS module gets an entry on the first run, the entry is used as
 * it is on the next, a changed module is compiled afresh (never its stale
 * code), and PATHTRACE_COMPILE_CACHE=0 turns it all off.
 */
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readdirSync, rmSync, statSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterEach, beforeEach, describe, expect, it } from 'vitest';

const SOURCE = new URL('../../src/cli/compileCache.ts', import.meta.url).pathname;

let dir: string;
beforeEach(() => {
  dir = mkdtempSync(join(tmpdir(), 'pathtrace-ccache-'));
  writeFileSync(join(dir, 'run.ts'), `import { createRequire } from 'node:module';\nimport { enableCompileCache } from ${JSON.stringify(SOURCE)};\nenableCompileCache();\nconst m = createRequire(import.meta.url)(process.argv[2]);\nconsole.log(JSON.stringify([m.value, m.helper(), m.here === ${JSON.stringify(dir)}]));\n`);
  writeFileSync(join(dir, 'helper.cjs'), 'module.exports = () => "helped";\n');
});
afterEach(() => rmSync(dir, { recursive: true, force: true }));

/** A module over the cache's size threshold that requires a relative file. */
function writeBig(value: number): void {
  const pad = 'x'.repeat(100_000);
  writeFileSync(join(dir, 'big.cjs'), `const helper = require('./helper.cjs');\nmodule.exports = { value: ${value}, helper, here: __dirname, pad: '${pad}' };\n`);
}

function runChild(extraEnv: Record<string, string> = {}): unknown {
  const env = { ...process.env, XDG_CACHE_HOME: join(dir, 'cache'), PATHTRACE_COMPILE_CACHE: '', ...extraEnv };
  return JSON.parse(execFileSync(process.execPath, ['--import', 'tsx', join(dir, 'run.ts'), join(dir, 'big.cjs')], { env, encoding: 'utf8' }));
}

const entries = () => {
  const root = join(dir, 'cache', 'pathtrace');
  if (!existsSync(root)) return [];
  return readdirSync(root).flatMap((v8) => readdirSync(join(root, v8)).map((f) => join(root, v8, f)));
};

describe('compile cache', () => {
  it('writes an entry, uses it unchanged, and recompiles a changed module', () => {
    writeBig(1);
    expect(runChild()).toEqual([1, 'helped', true]);
    const [entry] = entries();
    expect(entries()).toHaveLength(1);
    const first = statSync(entry).mtimeMs;
    expect(runChild()).toEqual([1, 'helped', true]);
    expect(statSync(entry).mtimeMs).toBe(first); // accepted: not written again
    writeBig(2); // same length, other code
    expect(runChild()).toEqual([2, 'helped', true]);
    expect(entries()).toEqual([entry]);
    expect(runChild()).toEqual([2, 'helped', true]);
  }, 60_000);

  it('PATHTRACE_COMPILE_CACHE=0: no cache', () => {
    writeBig(3);
    expect(runChild({ PATHTRACE_COMPILE_CACHE: '0' })).toEqual([3, 'helped', true]);
    expect(entries()).toEqual([]);
  }, 60_000);
});
