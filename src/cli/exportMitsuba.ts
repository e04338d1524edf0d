/**
 * `pathtrace export-mitsuba SCENE.json [-o OUT.xml]`: the scene as a Mitsuba 3
 * XML document, on stdout or written atomically to OUT.xml.
 */
import { dirname, resolve } from 'node:path';
import { meshPlyFile, toMitsubaXml, type MitsubaExportOptions } from '../scene/mitsuba';
import { MAX_IMAGE_SIZE } from '../scene/limits';
import { MAX_SEED, MAX_SPP, parseInteger, parsePositiveInteger, resolveSize } from './args';
import { usageError } from './errors';
import { checkWritable, writeFileAtomic } from './output';
import { loadSceneFile, loadSceneFiles, type TextSink } from './validate';

export interface RawExportOptions {
  output?: string;
  spp?: string;
  seed?: string;
  width?: string;
  height?: string;
}

function parseExportOptions(raw: RawExportOptions): { spp?: number; seed?: number; width?: number; height?: number } {
  const problems: string[] = [];
  const attempt = (fn: () => number): number | undefined => {
    try {
      return fn();
    } catch (error) {
      problems.push(...((error as { lines?: string[] }).lines ?? [String(error)]));
      return undefined;
    }
  };
  const out = {
    spp: raw.spp === undefined ? undefined : attempt(() => parsePositiveInteger('--spp', raw.spp!, MAX_SPP)),
    seed: raw.seed === undefined ? undefined : attempt(() => parseInteger('--seed', raw.seed!, 0, MAX_SEED, 'a non-negative integer')),
    width: raw.width === undefined ? undefined : attempt(() => parsePositiveInteger('--width', raw.width!, MAX_IMAGE_SIZE)),
    height: raw.height === undefined ? undefined : attempt(() => parsePositiveInteger('--height', raw.height!, MAX_IMAGE_SIZE)),
  };
  if (problems.length > 0) throw usageError(problems);
  return out;
}

export async function exportMitsubaCommand(file: string, raw: RawExportOptions, stdout: TextSink, stderr: TextSink): Promise<void> {
  const options = parseExportOptions(raw);
  const scene = await loadSceneFile(file);
  if (raw.output !== undefined) await checkWritable('-o', raw.output);
  const exportOptions: MitsubaExportOptions = {};
  if (options.spp !== undefined) exportOptions.spp = options.spp;
  if (options.seed !== undefined) exportOptions.seed = options.seed;
  if (options.width !== undefined || options.height !== undefined) {
    Object.assign(exportOptions, resolveSize(scene.image, options));
  }
  const { assets } = await loadSceneFiles(file, scene);
  const base = raw.output === undefined ? 'scene' : raw.output.replace(/\.xml$/i, '');
  const meshFiles = scene.meshes.map((mesh, i) => ({ path: `${base}-mesh${i}.ply`, data: meshPlyFile(mesh, assets.meshes.get(mesh.file)!) }));
  exportOptions.environmentMapPath = (map) => resolve(dirname(file), map);
  exportOptions.meshPath = (i) => resolve(meshFiles[i].path);
  exportOptions.meshSmooth = (i) => assets.meshes.get(scene.meshes[i].file)!.normals !== null;
  for (const mesh of meshFiles) await writeFileAtomic(mesh.path, mesh.data);
  const xml = toMitsubaXml(scene, exportOptions);
  const text = xml.endsWith('\n') ? xml : `${xml}\n`;
  if (raw.output === undefined) {
    stdout.write(text);
    return;
  }
  await writeFileAtomic(raw.output, Buffer.from(text, 'utf8'));
  stderr.write(`wrote ${raw.output}\n`);
}
