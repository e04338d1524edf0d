/**
 * A V8 code cache for the CommonJS modules the CLI loads after start-up
 * (playwright-core: 7 MB of JavaScript that takes about half a second to
 * compile on every run). Node 22 has module.enableCompileCache(); on Node 20
 * the same is done here as v8-compile-cache does it: Module.prototype._compile
 * compiles through vm.Script with the cached data of an earlier run, and
 * writes fresh data at exit for the files that had none (or stale data).
 *
 * The cache lives in $XDG_CACHE_HOME/pathtrace (~/.cache/pathtrace), one file
 * per module path, headed by a hash of the module's source: a changed file
 * (an upgrade) is compiled afresh and its entry replaced. Any failure to read
 * or write the cache only means compiling as usual. PATHTRACE_COMPILE_CACHE=0
 * turns it off.
 */
import { createHash } from 'node:crypto';
import { mkdirSync, readFileSync, renameSync, writeFileSync } from 'node:fs';
import Module from 'node:module';
import { homedir } from 'node:os';
import { dirname, join } from 'node:path';
import vm from 'node:vm';

/** Modules smaller than this compile fast enough: no entry. */
const MIN_SOURCE_CHARS = 64 * 1024;
const HASH_BYTES = 20;

interface CjsModule {
  exports: unknown;
  require(id: string): unknown;
  _compile(content: string, filename: string): unknown;
}

interface ModuleInternals {
  prototype: CjsModule;
  wrap(source: string): string;
  _resolveFilename(request: string, parent: CjsModule, isMain: boolean, options?: unknown): string;
  _resolveLookupPaths(request: string, parent: CjsModule): string[] | null;
  _extensions: unknown;
  _cache: unknown;
}

let installed = false;

/** The cache directory, or undefined when there is no home to put it in. */
export function compileCacheDir(env: NodeJS.ProcessEnv = process.env): string | undefined {
  const base = env.XDG_CACHE_HOME || (homedir() ? join(homedir(), '.cache') : '');
  return base ? join(base, 'pathtrace', `v8-${process.versions.v8}`) : undefined;
}

/** Turns the cache on for modules loaded from now on (once per process; no-op when off or unavailable). */
export function enableCompileCache(env: NodeJS.ProcessEnv = process.env): void {
  if (installed || env.PATHTRACE_COMPILE_CACHE === '0') return;
  installed = true;
  const dir = compileCacheDir(env);
  if (!dir) return;
  const native = (Module as unknown as { enableCompileCache?: (dir: string) => unknown }).enableCompileCache;
  if (native) {
    try {
      native(dir);
    } catch {
      // No cache: compile as usual.
    }
    return;
  }
  try {
    mkdirSync(dir, { recursive: true, mode: 0o700 });
  } catch {
    return;
  }
  installHook(Module as unknown as ModuleInternals, dir);
}

function installHook(M: ModuleInternals, dir: string): void {
  const original = M.prototype._compile;
  const fresh: { file: string; hash: Buffer; script: vm.Script }[] = [];
  M.prototype._compile = function (this: CjsModule, content: string, filename: string) {
    if (content.length < MIN_SOURCE_CHARS) return original.call(this, content, filename);
    const file = join(dir, `${createHash('sha1').update(filename).digest('hex')}.bin`);
    const hash = createHash('sha1').update(content).digest();
    let cachedData: Buffer | undefined;
    try {
      const entry = readFileSync(file);
      if (entry.length > HASH_BYTES && entry.subarray(0, HASH_BYTES).equals(hash)) cachedData = entry.subarray(HASH_BYTES);
    } catch {
      // No entry yet.
    }
    let script: vm.Script;
    try {
      script = new vm.Script(M.wrap(content), {
        filename,
        cachedData,
        importModuleDynamically: vm.constants.USE_MAIN_CONTEXT_DEFAULT_LOADER,
      } as vm.ScriptOptions);
    } catch {
      return original.call(this, content, filename);
    }
    if (cachedData === undefined || script.cachedDataRejected) fresh.push({ file, hash, script });
    const wrapper = script.runInThisContext({ displayErrors: true }) as (...args: unknown[]) => unknown;
    const mod = this;
    const require = Object.assign((id: string) => mod.require(id), {
      resolve: Object.assign((request: string, options?: unknown) => M._resolveFilename(request, mod, false, options), {
        paths: (request: string) => M._resolveLookupPaths(request, mod),
      }),
      main: process.mainModule,
      extensions: M._extensions,
      cache: M._cache,
    });
    return wrapper.call(mod.exports, mod.exports, require, mod, filename, dirname(filename));
  };
  // At exit the scripts have run, so the data holds the functions compiled lazily too.
  process.once('exit', () => {
    for (const { file, hash, script } of fresh) {
      try {
        const temp = `${file}.${process.pid}.tmp`;
        writeFileSync(temp, Buffer.concat([hash, script.createCachedData()]), { mode: 0o600 });
        renameSync(temp, file);
      } catch {
        // Read-only or full: next time compiles as usual.
      }
    }
  });
}
