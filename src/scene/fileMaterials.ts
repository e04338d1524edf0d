/**
 * A scene as the renderer draws it: every mesh with one material. A mesh
 * whose `material` is null (version 3 without the key) wears its file's own
 * materials (glTF's, an OBJ's MTL): it becomes one mesh per material it
 * uses, each the file's triangles of that material under a name of its own
 * (`file#material3`), so everything downstream (packing, instancing,
 * emitters, the exporter) keeps one material per mesh. A file without
 * materials takes the default material. The file's lights (glTF
 * KHR_lights_punctual) join the scene's, placed by the mesh's transform.
 *
 * Texture images of file materials are named, in the resolved scene and in
 * SceneAssets.images, by `fileImageName`: the file's embedded image `#N` as
 * `file#N`, an image beside the file by its path relative to the scene.
 * Pure TypeScript; the subsets are cached per decoded file, so resolving
 * after an edit costs nothing for meshes that did not change.
 */
import { defaultMaterial, materialTextures, type Material } from '../materials/registry';
import type { Light } from '../lights/registry';
import type { SceneAssets } from './assets';
import { applyMatrix, meshToWorldMatrix } from './mesh/transform';
import type { FileMaterial, Mesh, Scene, TriangleMesh, Vec3 } from './types';

export interface ResolvedMesh extends Mesh {
  material: Material;
  /** The index of the scene mesh it comes from. */
  source: number;
  /**
   * Whether its material's base color is multiplied by its file's vertex
   * colors (a file material with glTF COLOR_0, whose subset has `colors`);
   * false for a scene's own material, which never uses them.
   */
  vertexColors: boolean;
}

/** A mesh as the renderer takes it: its one material, and whether that multiplies by the vertex colors (absent: no). */
export type RenderMesh = Mesh & { material: Material; vertexColors?: boolean };
/** A scene whose every mesh has its one material: what the renderer and the exporter take. */
export type RenderScene = Omit<Scene, 'meshes'> & { meshes: RenderMesh[] };
export type ResolvedScene = Omit<Scene, 'meshes'> & { meshes: ResolvedMesh[] };

/**
 * The scene as a RenderScene, checked: every mesh must have its material
 * (a mesh wearing its file's must be resolved first, by resolveFileMaterials).
 */
export function asRenderScene(scene: Scene | RenderScene, caller: string): RenderScene {
  scene.meshes.forEach((mesh, i) => {
    if (!mesh.material) throw new Error(`${caller}: meshes[${i}] wears its file's materials: pass resolveFileMaterials(scene, assets).scene`);
  });
  return scene as RenderScene;
}

/** The name of a file material's image as the scene's assets hold it: `#N` embedded in `meshFile`, else beside it. */
export function fileImageName(meshFile: string, image: string): string {
  if (image.startsWith('#')) return `${meshFile}${image}`;
  return joinPath(folderOf(meshFile), image);
}

/** The scene-relative path of `file` in `folder` ('' = the scene's own folder), with `.` and `..` steps folded. */
export function joinPath(folder: string, file: string): string {
  if (/^([a-z]+:|\/)/i.test(file)) return file;
  const parts = `${folder}${folder ? '/' : ''}${file}`.split('/');
  const out: string[] = [];
  for (const part of parts) {
    if (part === '.' || part === '') continue;
    if (part === '..' && out.length > 0 && out[out.length - 1] !== '..') out.pop();
    else out.push(part);
  }
  return out.join('/');
}

const folderOf = (file: string) => {
  const slash = Math.max(file.lastIndexOf('/'), file.lastIndexOf('\\'));
  return slash < 0 ? '' : file.slice(0, slash);
};

/** Whether the mesh wears its file's own materials (the file has some and the scene gives none). */
export const wearsFileMaterials = (mesh: Mesh, data: TriangleMesh | undefined): boolean => mesh.material === null && !!data?.fileMaterials;

/** The file materials a mesh wears, by index, with their images named as the scene's assets name them. */
export function fileMaterialsOf(mesh: Mesh, data: TriangleMesh | undefined): FileMaterial[] {
  if (!wearsFileMaterials(mesh, data)) return [];
  return data!.fileMaterials!.materials.map((m) => ({ ...m, material: renameImages(m.material, (image) => fileImageName(mesh.file, image)) }));
}

const subsetCache = new WeakMap<TriangleMesh, Map<number, TriangleMesh>>();

/** The scene with every mesh's material resolved, and the assets that name its subsets. */
export function resolveFileMaterials(scene: Scene, assets: SceneAssets): { scene: ResolvedScene; assets: SceneAssets } {
  const meshes: ResolvedMesh[] = [];
  const subsets = new Map<string, TriangleMesh>();
  const lights: Light[] = [...scene.lights];
  scene.meshes.forEach((mesh, i) => {
    const data = assets.meshes.get(mesh.file);
    if (data?.lights?.length) lights.push(...data.lights.map((l) => placeLight(l, mesh)));
    if (!wearsFileMaterials(mesh, data)) {
      meshes.push({ ...mesh, material: mesh.material ?? defaultMaterial(), source: i, vertexColors: false });
      return;
    }
    const own = fileMaterialsOf(mesh, data);
    for (const k of usedMaterials(data!)) {
      const file = `${mesh.file}#material${k}`;
      const subset = materialSubset(data!, k, own[k].uvSet);
      subsets.set(file, subset);
      meshes.push({ ...mesh, file, material: own[k].material, source: i, vertexColors: own[k].vertexColors && !!subset.colors });
    }
  });
  // A mesh without material on a file that has none gets the default: the scene changes then too.
  const unchanged = subsets.size === 0 && lights.length === scene.lights.length && scene.meshes.every((m) => m.material);
  if (unchanged) return { scene: scene as ResolvedScene, assets };
  return { scene: { ...scene, lights, meshes }, assets: subsets.size === 0 ? assets : { ...assets, meshes: new Map([...assets.meshes, ...subsets]) } };
}

/** The material indices a file's triangles use, in order. */
function usedMaterials(data: TriangleMesh): number[] {
  const used = new Set<number>(data.fileMaterials!.triangles);
  return [...used].sort((a, b) => a - b);
}

/** The triangles of material k, their vertices compacted, reading coordinate set `uvSet` as `uvs` (cached). */
function materialSubset(data: TriangleMesh, k: number, uvSet: 0 | 1): TriangleMesh {
  let byMaterial = subsetCache.get(data);
  if (!byMaterial) subsetCache.set(data, (byMaterial = new Map()));
  let subset = byMaterial.get(k);
  if (!subset) byMaterial.set(k, (subset = extractSubset(data, k, uvSet)));
  return subset;
}

function extractSubset(data: TriangleMesh, k: number, uvSet: 0 | 1): TriangleMesh {
  const triangles = data.fileMaterials!.triangles;
  const uvs = uvSet === 1 ? (data.uvs1 ?? null) : (data.uvs ?? null);
  const remap = new Int32Array(data.positions.length / 3).fill(-1);
  const order: number[] = [];
  const indices: number[] = [];
  for (let t = 0; t < triangles.length; t++) {
    if (triangles[t] !== k) continue;
    for (let c = 0; c < 3; c++) {
      const v = data.indices[3 * t + c];
      if (remap[v] < 0) remap[v] = order.push(v) - 1;
      indices.push(remap[v]);
    }
  }
  const pick = (source: Float32Array | null | undefined, n: number) => {
    if (!source) return null;
    const out = new Float32Array(order.length * n);
    order.forEach((v, i) => out.set(source.subarray(v * n, v * n + n), i * n));
    return out;
  };
  const subset: TriangleMesh = {
    positions: pick(data.positions, 3)!,
    normals: pick(data.normals, 3),
    indices: Uint32Array.from(indices),
    uvs: pick(uvs, 2),
    uvs1: null,
    tangents: pick(data.tangents, 4),
  };
  const colors = pick(data.colors, 3);
  if (colors) subset.colors = colors;
  return subset;
}

/** A deep copy of a material with each texture's image renamed. */
function renameImages(material: Material, rename: (image: string) => string): Material {
  const copy = structuredClone(material);
  for (const t of materialTextures(copy)) t.texture.image = rename(t.texture.image);
  return copy;
}

/** A file's light in the scene: its position, target and direction through the mesh's transform. */
function placeLight(light: Light, mesh: Mesh): Light {
  const m = meshToWorldMatrix(mesh);
  const point = (p: Vec3): Vec3 => Array.from(applyMatrix(m, p, null).positions) as Vec3;
  const placed = { ...light } as Record<string, unknown>;
  if ('position' in light) placed.position = point(light.position as Vec3);
  if ('target' in light) placed.target = point(light.target as Vec3);
  if ('direction' in light) {
    const [x, y, z] = light.direction as Vec3;
    const d = [m[0] * x + m[4] * y + m[8] * z, m[1] * x + m[5] * y + m[9] * z, m[2] * x + m[6] * y + m[10] * z];
    const length = Math.hypot(d[0], d[1], d[2]) || 1;
    placed.direction = d.map((c) => c / length);
  }
  return placed as unknown as Light;
}
