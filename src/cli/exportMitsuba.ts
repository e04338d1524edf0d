/**
 * `pathtrace export-mitsuba SCENE.json [-o OUT.xml]`: the scene as a Mitsuba 3
 * XML document, on stdout or written atomically to OUT.xml. The files it
 * names are written beside OUT.xml, named after it: `OUT-mesh<i>.ply` per
 * mesh and `OUT-tex<k>-<image>-<use>.pfm` per baked texture (with stdout,
 * meshes go to `scene-mesh<i>.ply` in the working folder; a textured scene
 * needs -o, so that its images have a place beside the XML), and a page's
 * bundled map that is not beside the scene as `OUT-NAME.exr`.
 */
import { existsSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { bundledMapBytes, bundledMapName } from '../app/bundledMaps';
import { materialTextures } from '../materials/registry';
import { bakedTextureFile, exportMitsuba, meshPlyFile, type MitsubaExportOptions } from '../scene/mitsuba';
import { resolveFileMaterials, type RenderScene } from '../scene/fileMaterials';
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

/** The scene path of the first texture the scene's materials read, if any (`ground.material.baseColor`). */
function firstTexture(scene: RenderScene): string | undefined {
  const materials = [...(scene.ground ? [{ path: 'ground.material', material: scene.ground.material }] : []), ...scene.meshes.map((m, i) => ({ path: `meshes[${i}].material`, material: m.material }))];
  for (const { path, material } of materials) {
    const [texture] = materialTextures(material);
    if (texture) return `${path}.${texture.key}`;
  }
  return undefined;
}

/**
 * A page's bundled map (`bundled/studio.exr`) that is not beside the scene
 * (the CLI renders it from the bundle: src/node/sceneFiles.ts) is written
 * beside the XML for Mitsuba, as `OUT-studio.exr`.
 */
async function bundledMapCopy(file: string, scene: RenderScene, base: string): Promise<{ path: string; data: Uint8Array } | undefined> {
  const map = scene.environment && 'map' in scene.environment ? scene.environment.map : undefined;
  const name = map === undefined ? null : bundledMapName(map);
  if (name === null || existsSync(resolve(dirname(file), map!))) return undefined;
  return { path: `${base}-${name}.exr`, data: await bundledMapBytes(name) };
}

export async function exportMitsubaCommand(file: string, raw: RawExportOptions, stdout: TextSink, stderr: TextSink): Promise<void> {
  const options = parseExportOptions(raw);
  const sceneModel = await loadSceneFile(file);
  // Meshes wearing their files' materials become one mesh (one PLY) per material.
  const loaded = await loadSceneFiles(file, sceneModel);
  const { scene, assets } = resolveFileMaterials(sceneModel, loaded.assets);
  const textured = firstTexture(scene);
  if (raw.output === undefined && textured !== undefined) {
    throw usageError(`${file}: ${textured} is a texture, which the export bakes into image files beside the XML: pass -o OUT.xml`);
  }
  if (raw.output !== undefined) await checkWritable('-o', raw.output);
  const exportOptions: MitsubaExportOptions = {};
  if (options.spp !== undefined) exportOptions.spp = options.spp;
  if (options.seed !== undefined) exportOptions.seed = options.seed;
  if (options.width !== undefined || options.height !== undefined) {
    Object.assign(exportOptions, resolveSize(scene.image, options));
  }
  const base = raw.output === undefined ? 'scene' : raw.output.replace(/\.xml$/i, '');
  const meshFiles = scene.meshes.map((mesh, i) => ({ path: `${base}-mesh${i}.ply`, data: meshPlyFile(mesh, assets.meshes.get(mesh.file)!) }));
  const bundledMap = await bundledMapCopy(file, scene, base);
  exportOptions.environmentMapPath = (map) => (bundledMap ? resolve(bundledMap.path) : resolve(dirname(file), map));
  exportOptions.meshPath = (i) => resolve(meshFiles[i].path);
  exportOptions.meshSmooth = (i) => assets.meshes.get(scene.meshes[i].file)!.normals !== null;
  exportOptions.images = assets.images;
  const texturePath = (name: string) => `${base}-${name}`;
  exportOptions.texturePath = (name) => resolve(texturePath(name));
  const { xml, textures } = exportMitsuba(scene, exportOptions);
  for (const mesh of meshFiles) await writeFileAtomic(mesh.path, mesh.data);
  if (bundledMap) await writeFileAtomic(bundledMap.path, bundledMap.data);
  for (const texture of textures) await writeFileAtomic(texturePath(texture.name), bakedTextureFile(texture));
  const text = xml.endsWith('\n') ? xml : `${xml}\n`;
  if (raw.output === undefined) {
    stdout.write(text);
    return;
  }
  await writeFileAtomic(raw.output, Buffer.from(text, 'utf8'));
  stderr.write(`wrote ${raw.output}\n`);
}
