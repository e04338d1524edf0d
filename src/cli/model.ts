/**
 * A model file given where a scene file goes (`pathtrace render model.glb`,
 * `pathtrace scene model.glb`): the scene around it (src/scene/modelScene.ts)
 * with the model fitted on a grey ground, framed by the default camera or
 * seen by one of the file's glTF cameras (--camera), lit by the bundled
 * studio map or another (--env). The scene is made as JSON text and parsed
 * back, so rendering the model and rendering the scene `pathtrace scene`
 * prints are the same render.
 */
import { readFile, stat } from 'node:fs/promises';
import path from 'node:path';
import { parsePositiveInteger, resolveSize } from './args';
import { CliError, usageError } from './errors';
import { checkWritable, writeFileAtomic } from './output';
import { loadSceneFiles, type TextSink } from './validate';
import type { SceneFiles } from '../node/sceneFiles';
import { AssetError } from '../scene/assetError';
import { MAX_IMAGE_SIZE } from '../scene/limits';
import { readGltfCameras, type GltfCamera } from '../scene/mesh/gltfCameras';
import { MODEL_IMAGE, modelSceneDocument, modelSceneJson, STUDIO_INTENSITY, STUDIO_MAP } from '../scene/modelScene';
import { parseScene, parseSceneText } from '../scene/schema';
import type { Scene, TriangleMesh } from '../scene/types';

/** The flags that shape a model's scene (render and scene both take them). */
export interface RawModelOptions {
  width?: string;
  height?: string;
  /** --camera (true: the first) or --camera N. */
  camera?: string | boolean;
  /** --env FILE or --env none. */
  env?: string;
}

export interface ModelScene {
  scene: Scene;
  /** The scene as JSON text, as `pathtrace scene` prints it. */
  text: string;
  /** Where the scene would live: the files it names are relative to this file's folder. */
  sceneFile: string;
}

/**
 * The extensions decodeMesh reads (MESH_EXTENSIONS of src/scene/mesh, which a
 * unit test compares): not imported, so that a start-up of the CLI does not
 * load glTF-Transform and Draco before it needs them.
 */
export const MODEL_EXTENSIONS = ['.obj', '.ply', '.gltf', '.glb'] as const;

/** Whether a render/scene argument is a model file rather than a scene file (by its extension). */
export function isModelFile(file: string): boolean {
  const extension = path.extname(file).toLowerCase();
  return (MODEL_EXTENSIONS as readonly string[]).includes(extension);
}

/** --camera and --env belong to model files: with a scene file they are an error. */
export function checkNoModelOptions(file: string, raw: RawModelOptions): void {
  const given = [raw.camera !== undefined ? '--camera' : null, raw.env !== undefined ? '--env' : null].filter((f) => f !== null);
  if (given.length > 0) {
    throw usageError(`${given.join(', ')}: only for a model file (${MODEL_EXTENSIONS.join(', ')}), not a scene file (got ${JSON.stringify(file)})`);
  }
}

/**
 * The scene for `modelFile`, as if saved as `sceneFile` (its folder decides
 * the relative paths it writes). Every problem is a usage error: the model
 * (`model.glb: ...`), --camera, --env, --width/--height are checked by the caller.
 */
export async function loadModelScene(modelFile: string, raw: RawModelOptions, sceneFile: string, size: { width?: number; height?: number }): Promise<ModelScene> {
  const bytes = await readModel(modelFile);
  const data = await decodeModel(modelFile, bytes);
  const camera = raw.camera === undefined ? undefined : chooseCamera(modelFile, bytes, raw.camera);
  const folder = path.dirname(path.resolve(sceneFile));
  const relative = (file: string) => path.relative(folder, path.resolve(file)).split(path.sep).join('/');
  if (raw.env !== undefined && raw.env.trim() === '') throw usageError('--env: must name an environment map (.hdr, .exr) or be none (got "")');
  const env = raw.env === undefined ? STUDIO_MAP : raw.env === 'none' ? null : relative(raw.env);
  const document = modelSceneDocument({
    file: relative(modelFile),
    data,
    image: resolveSize(MODEL_IMAGE, size),
    environmentMap: env,
    environmentIntensity: raw.env === undefined ? STUDIO_INTENSITY : 1,
    camera,
  });
  let text: string;
  try {
    text = formatSceneJson(modelSceneJson(parseScene(document)));
  } catch (error) {
    // Only a camera the file places oddly (a degenerate node matrix) gets here.
    throw usageError(`${modelFile}: cannot make a scene for it (${(error as Error)?.message?.split('\n')[0]})`, error);
  }
  return { scene: parseSceneText(text), text, sceneFile };
}

/**
 * The files a model's scene names (the model, the map), read and decoded;
 * problems name the model file or --env, which is what the user gave.
 */
export async function loadModelFiles(modelFile: string, model: ModelScene): Promise<SceneFiles> {
  try {
    return await loadSceneFiles(model.sceneFile, model.scene);
  } catch (error) {
    if (!(error instanceof CliError)) throw error;
    const lines = error.lines.map((line) => line.replace(/^meshes\[0\]\.file: /, `${modelFile}: `).replace(/^environment\.map: /, '--env: '));
    throw new CliError(error.exitCode, lines, { cause: error });
  }
}

async function readModel(file: string): Promise<Uint8Array> {
  try {
    const info = await stat(file);
    if (info.isDirectory()) throw usageError(`${file}: cannot read model: is a directory`);
    return new Uint8Array(await readFile(file));
  } catch (error) {
    if (error instanceof CliError) throw error;
    const code = (error as NodeJS.ErrnoException)?.code;
    const reason = code === 'ENOENT' ? 'no such file' : code === 'EACCES' || code === 'EPERM' ? 'permission denied' : (error as Error)?.message?.split('\n')[0];
    throw usageError(`${file}: cannot read model: ${reason}`, error);
  }
}

async function decodeModel(file: string, bytes: Uint8Array): Promise<TriangleMesh> {
  const folder = path.dirname(path.resolve(file));
  const { decodeMesh } = await import('../scene/mesh');
  try {
    return await decodeMesh(bytes, file, {
      resolveResource: async (uri) => new Uint8Array(await readFile(path.resolve(folder, decodeURIComponent(uri)))),
    });
  } catch (error) {
    const message = error instanceof AssetError ? error.message : `cannot be read (${(error as Error)?.message?.split('\n')[0] ?? String(error)})`;
    throw usageError(`${file}: ${message}`, error);
  }
}

/** The glTF camera `--camera` names (true: the first; N: the file's cameras[N]), checked usable. */
export function chooseCamera(file: string, bytes: Uint8Array, flag: string | boolean): GltfCamera {
  const extension = path.extname(file).toLowerCase();
  if (extension !== '.glb' && extension !== '.gltf') throw usageError(`--camera: ${file} is not a glTF file; only glTF files carry cameras`);
  let index = 0;
  if (typeof flag === 'string') {
    if (!/^\d+$/.test(flag.trim())) throw usageError(`--camera: must be a camera index, a non-negative integer (got ${JSON.stringify(flag)})`);
    index = Number(flag.trim());
  }
  let cameras: GltfCamera[];
  try {
    cameras = readGltfCameras(bytes, extension === '.glb');
  } catch (error) {
    throw usageError(`${file}: ${(error as Error).message}`, error);
  }
  if (cameras.length === 0) throw usageError(`--camera: ${file} has no cameras`);
  if (index >= cameras.length) throw usageError(`--camera: ${file} has ${cameras.length} camera${cameras.length === 1 ? '' : 's'} (0 to ${cameras.length - 1}) (got ${index})`);
  const camera = cameras[index];
  const label = `--camera: camera ${index}${camera.name ? ` ("${camera.name}")` : ''} of ${file}`;
  if (camera.type !== 'perspective') throw usageError(`${label} is not a perspective camera; only perspective cameras are supported`);
  const yfov = camera.yfov ?? NaN;
  if (!(yfov > 0 && yfov < Math.PI)) throw usageError(`${label} has yfov ${yfov}; it must be between 0 and pi radians`);
  if (!camera.world) throw usageError(`${label} is placed by no node of the file's scene`);
  return camera;
}

/** Two-space JSON with every [x, y, z] on one line, as stringifyScene (serialize.ts) writes scenes. */
export function formatSceneJson(json: unknown): string {
  const text = JSON.stringify(json, null, 2);
  return `${text.replace(/\[\s+(-?[\d.eE+-]+),\s+(-?[\d.eE+-]+),\s+(-?[\d.eE+-]+)\s+\]/g, '[$1, $2, $3]')}\n`;
}

/** Where a model's scene lives when no file is written: `MODEL.json` in the current directory (or `cwd`). */
export function modelScenePath(modelFile: string, cwd?: string): string {
  const stem = path.basename(modelFile, path.extname(modelFile)) || 'model';
  return path.resolve(cwd ?? process.cwd(), `${stem}.json`);
}

export interface RawSceneOptions extends RawModelOptions {
  output?: string;
}

/**
 * `pathtrace scene MODEL`: prints the scene `pathtrace render MODEL` renders
 * (paths relative to the current directory), or writes it to -o (paths
 * relative to that file's folder). Reads the files it names, as render
 * does, so a scene it prints is one that renders.
 */
export async function sceneCommand(modelFile: string, raw: RawSceneOptions, io: { stdout: TextSink; stderr: TextSink; cwd?: string }): Promise<void> {
  if (!isModelFile(modelFile)) throw usageError(`${modelFile}: not a model file (use ${MODEL_EXTENSIONS.join(', ')})`);
  const size = parseSize(raw);
  if (raw.output !== undefined) await checkWritable('-o', raw.output);
  const sceneFile = raw.output === undefined ? modelScenePath(modelFile, io.cwd) : path.resolve(raw.output);
  const model = await loadModelScene(modelFile, raw, sceneFile, size);
  await loadModelFiles(modelFile, model);
  if (raw.output === undefined) {
    io.stdout.write(model.text);
    return;
  }
  await writeFileAtomic(raw.output, Buffer.from(model.text, 'utf8'));
  io.stderr.write(`wrote ${raw.output}\n`);
}

function parseSize(raw: RawModelOptions): { width?: number; height?: number } {
  const problems: string[] = [];
  const parse = (flag: string, value: string | undefined) => {
    if (value === undefined) return undefined;
    try {
      return parsePositiveInteger(flag, value, MAX_IMAGE_SIZE);
    } catch (error) {
      problems.push(...((error as CliError).lines ?? [String(error)]));
      return undefined;
    }
  };
  const size = { width: parse('--width', raw.width), height: parse('--height', raw.height) };
  if (problems.length > 0) throw usageError(problems);
  return size;
}
