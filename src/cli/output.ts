/**
 * Output files: checked before rendering (so a bad -o fails in milliseconds,
 * not after minutes of rendering) and written atomically (a temp file in the
 * same directory, renamed over the target only once it is complete).
 */
import { constants as fsConstants } from 'node:fs';
import { access, open, rename, stat, unlink } from 'node:fs/promises';
import { basename, dirname, extname, join, resolve } from 'node:path';
import { failure, usageError } from './errors';

/** `dir/SCENE.json` -> `SCENE.png` in the current directory (or in `cwd` when given). */
export function defaultPngPath(scenePath: string, cwd?: string): string {
  const base = basename(scenePath);
  const ext = extname(base);
  const stem = ext === '' ? base : base.slice(0, -ext.length);
  const name = `${stem || 'render'}.png`;
  return cwd === undefined ? name : join(cwd, name);
}

function reason(error: unknown): string {
  const code = (error as NodeJS.ErrnoException | undefined)?.code;
  switch (code) {
    case 'ENOENT':
      return 'no such file or directory';
    case 'ENOTDIR':
      return 'a parent is not a directory';
    case 'EACCES':
    case 'EPERM':
      return 'permission denied';
    case 'EROFS':
      return 'read-only file system';
    case 'ENOSPC':
      return 'no space left on device';
    case 'EISDIR':
      return 'is a directory';
    case 'EDQUOT':
      return 'disk quota exceeded';
    default:
      return (error as Error | undefined)?.message?.split('\n')[0] ?? String(error);
  }
}

/**
 * Checks that `path` can be written: its directory exists and is writable,
 * and the path itself is not a directory. Throws a usage error (exit 2)
 * naming the flag, the path and what is wrong.
 */
export async function checkWritable(flag: string, path: string): Promise<void> {
  const target = resolve(path);
  const dir = dirname(target);
  let dirStat;
  try {
    dirStat = await stat(dir);
  } catch (error) {
    throw usageError(`${flag}: cannot write ${path}: directory ${dir}: ${reason(error)}`, error);
  }
  if (!dirStat.isDirectory()) throw usageError(`${flag}: cannot write ${path}: ${dir} is not a directory`);
  try {
    await access(dir, fsConstants.W_OK | fsConstants.X_OK);
  } catch (error) {
    throw usageError(`${flag}: cannot write ${path}: directory ${dir}: ${reason(error)}`, error);
  }
  const existing = await stat(target).catch(() => undefined);
  if (existing?.isDirectory()) throw usageError(`${flag}: cannot write ${path}: it is a directory`);
  if (existing !== undefined) {
    try {
      await access(target, fsConstants.W_OK);
    } catch (error) {
      // rename() can still replace a read-only file in a writable directory, but
      // overwriting a file the user protected is almost certainly not wanted.
      throw usageError(`${flag}: cannot write ${path}: ${reason(error)}`, error);
    }
  }
}

/** A temp name beside the target: same directory, so rename() is atomic. */
export function tempPathFor(path: string): string {
  const target = resolve(path);
  const random = Math.random().toString(36).slice(2, 10);
  return join(dirname(target), `.${basename(target)}.${process.pid}.${random}.tmp`);
}

/**
 * Writes `data` to `path` atomically: temp file, fsync, rename. On failure the
 * temp file is removed, any existing `path` is left untouched, and the error
 * is a one-line failure (exit 1) naming the file.
 */
export async function writeFileAtomic(path: string, data: Uint8Array): Promise<void> {
  await writeOutputs([{ path, data }]);
}

/**
 * Writes several files atomically as a group: every temp file is written and
 * synced first, and only then are they renamed over their targets, so a
 * failure (disk full, say) leaves every existing output as it was.
 */
export async function writeOutputs(files: { path: string; data: Uint8Array }[]): Promise<void> {
  const temps: { temp: string; file: { path: string; data: Uint8Array } }[] = [];
  const cleanUp = () => Promise.all(temps.map(({ temp }) => unlink(temp).catch(() => undefined)));
  for (const file of files) {
    const temp = tempPathFor(file.path);
    try {
      const handle = await open(temp, 'wx', 0o666);
      temps.push({ temp, file });
      try {
        await handle.writeFile(file.data);
        await handle.sync();
      } finally {
        await handle.close();
      }
    } catch (error) {
      await cleanUp();
      throw failure(`cannot write ${file.path}: ${reason(error)}`, error);
    }
  }
  for (let i = 0; i < temps.length; i++) {
    const { temp, file } = temps[i];
    try {
      await rename(temp, resolve(file.path));
    } catch (error) {
      await Promise.all(temps.slice(i).map(({ temp: t }) => unlink(t).catch(() => undefined)));
      throw failure(`cannot write ${file.path}: ${reason(error)}`, error);
    }
  }
}
