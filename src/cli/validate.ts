/**
 * `pathtrace validate SCENE.json`, and the scene-file loading every command
 * shares: read the file, parse and validate it, and turn each problem into
 * one `path: message` line (exit 2).
 */
import { readFile, stat } from 'node:fs/promises';
import { MAX_SCENE_BYTES } from '../scene/limits';
import { parseSceneText } from '../scene/schema';
import { readSceneFiles, type SceneFiles } from '../node/sceneFiles';
import type { Scene } from '../scene/types';
import { CliError, usageError } from './errors';

export interface TextSink {
  write(chunk: string): unknown;
}

function readReason(error: unknown): string {
  switch ((error as NodeJS.ErrnoException | undefined)?.code) {
    case 'ENOENT':
      return 'no such file';
    case 'EISDIR':
      return 'is a directory, not a scene file';
    case 'EACCES':
    case 'EPERM':
      return 'permission denied';
    case 'ENOTDIR':
      return 'a parent is not a directory';
    default:
      return (error as Error | undefined)?.message?.split('\n')[0] ?? String(error);
  }
}

/** The `issues` of a SceneError (checked structurally, so a duplicate module instance still matches). */
function sceneIssues(error: unknown): { path: string; message: string }[] | undefined {
  const issues = (error as { issues?: unknown } | null)?.issues;
  if (!Array.isArray(issues) || issues.length === 0) return undefined;
  return issues.map((issue: { path?: unknown; message?: unknown }) => ({
    path: typeof issue?.path === 'string' ? issue.path : '',
    message: typeof issue?.message === 'string' ? issue.message : String(issue),
  }));
}

/**
 * One line per problem, `path: message`. A problem with the whole document
 * (an empty path: JSON syntax, size) is reported against the file name instead.
 */
export function formatSceneIssues(file: string, issues: { path: string; message: string }[]): string[] {
  return issues.map(({ path, message }) => `${path === '' ? file : path}: ${message}`);
}

/** Reads and validates a scene file. Every failure is a usage error (exit 2) naming the file or field. */
export async function loadSceneFile(file: string): Promise<Scene> {
  let text: string;
  try {
    const info = await stat(file);
    if (info.isDirectory()) throw Object.assign(new Error('is a directory'), { code: 'EISDIR' });
    if (info.isFile() && info.size > MAX_SCENE_BYTES) {
      throw usageError(`${file}: scene file is ${info.size} bytes, larger than the limit of ${MAX_SCENE_BYTES}`);
    }
    text = await readFile(file, 'utf8');
  } catch (error) {
    if (error instanceof CliError) throw error;
    throw usageError(`${file}: cannot read scene: ${readReason(error)}`, error);
  }
  if (text.charCodeAt(0) === 0xfeff) text = text.slice(1);
  try {
    return parseSceneText(text);
  } catch (error) {
    const issues = sceneIssues(error);
    if (issues) throw usageError(formatSceneIssues(file, issues), error);
    throw usageError(`${file}: ${(error as Error)?.message ?? String(error)}`, error);
  }
}

/**
 * Reads and decodes the files a scene names (maps, meshes), relative to the
 * scene file: every unusable file is a usage error (exit 2), one line each,
 * found before rendering starts (render does this while Chromium starts).
 */
export async function loadSceneFiles(file: string, scene: Scene): Promise<SceneFiles> {
  try {
    return await readSceneFiles(scene, file);
  } catch (error) {
    const issues = sceneIssues(error);
    if (issues) throw usageError(formatSceneIssues(file, issues), error);
    throw error;
  }
}

/** A one-line summary of a valid scene, for `validate`. */
export function describeScene(file: string, scene: Scene): string {
  const plural = (n: number, word: string) => `${n} ${word}${n === 1 ? '' : 's'}`;
  const parts = [
    `${scene.image.width}x${scene.image.height}`,
    plural(scene.spheres.length, 'sphere'),
    plural(scene.lights.length, 'light'),
    ...(scene.meshes.length > 0 ? [plural(scene.meshes.length, 'mesh').replace(/meshs$/, 'meshes')] : []),
    scene.ground ? 'ground' : 'no ground',
    scene.environment ? ('map' in scene.environment ? `environment map ${scene.environment.map}` : 'environment') : 'black environment',
    `maxBounces ${scene.render.maxBounces}`,
  ];
  return `${file}: valid scene (${parts.join(', ')})`;
}

/** `pathtrace validate`: exit 0 and a summary on stdout, or exit 2 with one line per problem. */
export async function validateCommand(file: string, stdout: TextSink): Promise<void> {
  const scene = await loadSceneFile(file);
  await loadSceneFiles(file, scene);
  stdout.write(`${describeScene(file, scene)}\n`);
}
