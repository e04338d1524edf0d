/**
 * Meshes on the page: adding a model file to the scene (decoded, checked and
 * fitted before anything changes: a file that cannot be used changes
 * nothing), the selected mesh's panel controls (material and transform),
 * and the bundled example model (the npm package `bunny`).
 */
import type GUI from 'lil-gui';
import type { Controller } from 'lil-gui';
import { MAX_TRIANGLES } from '../render/bvh/pack';
import { groupMeshes, storedTriangles, trianglesIn } from '../render/bvh/groups';
import { AssetError } from '../scene/assetError';
import { defaultMaterial, materialSchema, materialTextures, normalizeMaterial } from '../materials/registry';
import { fileMaterialsOf, wearsFileMaterials } from '../scene/fileMaterials';
import { MAX_MESHES } from '../scene/limits';
import { formatIssue, type SceneIssue } from '../scene/schema';
import { meshWarnings, mergeAssets, type SceneAssets } from '../scene/assets';
import { encodePly, MESH_EXTENSIONS } from '../scene/mesh';
import { decodeMeshOffThread } from './meshDecode';
import type { Material, Mesh, Scene, TriangleMesh, Vec3 } from '../scene/types';
import { readUserFile } from './companionFiles';
import type { App } from './App';
import { addSphereMaterialControls, type TextureSlots } from './materialControls';
import { fitMesh, frameCamera, worldBoundingSphere } from './meshFit';
import { clearError, notify, showError } from './messages';
import { resolveAssets, type CompanionFiles } from './sceneLoader';

export const isModelFile = (name: string) => MESH_EXTENSIONS.some((ext) => name.toLowerCase().endsWith(ext));

/** Keeps the user's files with the autosave (Autosave.keepFiles: those the scene needs). */
export type KeepFiles = (files: CompanionFiles) => void;

/**
 * Adds a model file to the scene as a new mesh, fitted and framed, as one
 * undoable edit, and selects it. A model with materials of its own wears
 * them (`material` null, version 3); one without gets an editable default.
 * What it reads beside itself (a .gltf's .bin and images, an OBJ's .mtl)
 * comes from `companions`, the files opened with it. Returns whether it
 * was added; on failure an issue naming `meshes[i].file` is shown and
 * nothing changes. What the decoder ignored is shown as a notice.
 */
export async function addModelFile(app: App, file: File, keep: KeepFiles, companions: CompanionFiles = new Map()): Promise<boolean> {
  const index = app.scene.meshes.length;
  const failIssues = (issues: SceneIssue[]) => {
    showError(`The model "${file.name}" could not be added; the scene is unchanged.`, issues.map(formatIssue));
    return false;
  };
  const fail = (message: string) => failIssues([{ path: `meshes[${index}].file`, message: `${JSON.stringify(file.name)}: ${message}` }]);
  if (index >= MAX_MESHES) return fail(`the scene already has ${MAX_MESHES} meshes, the most it can hold`);
  let data: TriangleMesh;
  try {
    data = await decodeMeshOffThread(await readUserFile(file), file.name, companions);
  } catch (error) {
    return fail(error instanceof AssetError ? error.message : `cannot be read (${(error as Error)?.message ?? String(error)})`);
  }
  const name = fileNameFor(app, file.name, data);
  data = app.assets.meshes.get(name) ?? data;
  const material = data.fileMaterials ? null : { ...defaultMaterial(), roughness: 0.5 };
  const mesh: Mesh = { file: name, material, ...fitMesh(data, file.name, app.scene) };
  // A model already in the scene is stored once more only if it cannot be instanced (src/render/bvh/groups.ts).
  const trianglesOf = (f: string) => ((f === name ? data : app.assets.meshes.get(f))?.indices.length ?? 0) / 3;
  const triangles = storedTriangles({ ...app.scene, meshes: [...app.scene.meshes, mesh] }, trianglesOf);
  if (triangles > MAX_TRIANGLES) return fail(`the scene's meshes would have ${triangles} triangles; the most is ${MAX_TRIANGLES}`);
  // The images of its own materials (embedded, or beside it among the companions), checked with the scene.
  const files = new Map([...companions, [name, file]]);
  const candidate: Scene = { ...app.scene, version: 3, meshes: [...app.scene.meshes, mesh] };
  const loaded = await resolveAssets(candidate, files, mergeAssets(app.assets, { maps: new Map(), meshes: new Map([[name, data]]) }));
  if (!loaded.ok) return failIssues(loaded.issues);
  const bounds = worldBoundingSphere(mesh, data);
  const camera = frameCamera(app.scene.camera, bounds.center, bounds.radius, app.aspect);
  clearError();
  app.addAssets(loaded.assets);
  app.edit((s) => {
    s.version = Math.max(s.version, material ? 2 : 3) as Scene['version'];
    s.meshes.push(mesh);
    s.camera = camera;
  });
  app.select({ kind: 'mesh', index: app.scene.meshes.length - 1 });
  showMeshWarnings(app.scene, app.assets, index);
  keep(files);
  return true;
}

/** What the scene's model files' decoders ignored (or only mesh `only`'s), as a notice: the file still renders. */
export function showMeshWarnings(scene: Scene, assets: SceneAssets, only?: number): void {
  const warnings = meshWarnings(scene, assets).filter((w) => only === undefined || w.path === `meshes[${only}].file`);
  if (warnings.length > 0) notify(warnings.map(formatIssue).join(' '), 10_000);
}

/**
 * The name the scene gives the file: its own, unless a different model of
 * that name is already loaded (then "name-2.ext", ...). The same model again
 * keeps the name, so its decoded triangles are shared.
 */
function fileNameFor(app: App, name: string, data: TriangleMesh): string {
  const dot = name.lastIndexOf('.');
  for (let n = 1; ; n++) {
    const candidate = n === 1 ? name : `${name.slice(0, dot)}-${n}${name.slice(dot)}`;
    const loaded = app.assets.meshes.get(candidate);
    if (!loaded || sameTriangles(loaded, data)) return candidate;
  }
}

function sameTriangles(a: TriangleMesh, b: TriangleMesh): boolean {
  const equal = (x: ArrayLike<number> | null, y: ArrayLike<number> | null) => {
    if (x === null || y === null) return x === y;
    if (x.length !== y.length) return false;
    for (let i = 0; i < x.length; i++) if (x[i] !== y[i]) return false;
    return true;
  };
  return equal(a.positions, b.positions) && equal(a.indices, b.indices) && equal(a.normals, b.normals);
}

// ---------------------------------------------------------------- panel

/** How the BVH stores mesh i's triangles (src/render/bvh/groups.ts), for the panel. */
export function storedAs(app: App, i: number): string {
  const users = groupMeshes(app.scene, trianglesIn(app.assets)).shared.find((u) => u.includes(i));
  return users ? `once, for meshes ${users.map((k) => k + 1).join(', ')}` : 'a copy of its own';
}

/** The selected mesh's controls: its file, material (as a sphere's) and transform. */
export function addMeshControls(folder: GUI, app: App, mesh: () => Mesh, tracked: <T extends Controller>(c: T) => T, slots?: TextureSlots): void {
  folder.add({ file: mesh().file }, 'file').name('file').disable();
  // What the model costs: its triangles, and whether the BVH holds them once for several meshes or a copy for this one.
  const decoded = app.assets.meshes.get(mesh().file);
  const triangles = decoded ? (decoded.indices.length / 3).toLocaleString('en-US') : 'not loaded';
  folder.add({ triangles }, 'triangles').name('triangles').disable();
  folder.add({ stored: storedAs(app, app.scene.meshes.indexOf(mesh())) }, 'stored').name('stored').disable();
  addFileMaterialControls(folder, app, mesh);
  if (mesh().material) addSphereMaterialControls(folder, app, mesh as () => Mesh & { material: Material }, tracked, slots);
  const axis = (label: string, vector: () => Vec3, k: number, range?: [number, number, number]) => {
    const target = {
      get value() { return vector()[k]; },
      set value(v: number) { app.live(() => (vector()[k] = v)); },
    };
    // Shown to 3 decimals (a fitted model's position is not a round number); the value keeps its precision.
    const c = range ? folder.add(target, 'value', ...range) : folder.add(target, 'value').step(0.01).decimals(3);
    tracked(c.name(label));
  };
  ['x', 'y', 'z'].forEach((name, k) => axis(`position ${name}`, () => mesh().position, k));
  ['x', 'y', 'z'].forEach((name, k) => axis(`rotation ${name} (deg)`, () => mesh().rotation, k, [-180, 180, 1]));
  // One size factor: the per-axis ratios (a file's own or a JSON edit) are kept.
  tracked(folder.add({
    get scale() { const s = mesh().scale; return Math.cbrt(s[0] * s[1] * s[2]); },
    set scale(v: number) {
      if (!(v > 0)) return;
      app.live(() => {
        const s = mesh().scale;
        const factor = v / Math.cbrt(s[0] * s[1] * s[2]);
        mesh().scale = [s[0] * factor, s[1] * factor, s[2] * factor];
      });
    },
  }, 'scale').step(0.001).decimals(4).name('scale'));
}

/**
 * For a model with materials of its own: while the mesh wears them, each
 * one's name and the textures it uses (read-only) and "one material for
 * all", which gives the mesh one material (a principled default, then
 * edited as any); while it wears one, "the file's materials" to go back.
 * Each switch is one undoable edit.
 */
function addFileMaterialControls(folder: GUI, app: App, mesh: () => Mesh): void {
  const data = app.assets.meshes.get(mesh().file);
  const setMaterial = (material: Material | null) => {
    const i = app.scene.meshes.indexOf(mesh());
    if (i < 0) return;
    app.edit((s) => {
      s.meshes[i].material = material;
      if (material === null) s.version = 3;
    });
  };
  if (!data?.fileMaterials) {
    // A model without materials wearing the default one (version 3 without `material`): made editable.
    if (mesh().material === null) folder.add({ one: () => setMaterial(principledDefault()) }, 'one').name('one material for all');
    return;
  }
  if (!wearsFileMaterials(mesh(), data)) {
    folder.add({ wear: () => setMaterial(null) }, 'wear').name("the file's materials");
    return;
  }
  const used = new Set(data.fileMaterials.triangles);
  fileMaterialsOf(mesh(), data).forEach((m, k) => {
    if (!used.has(k)) return; // a material no triangle wears (glTF's default for primitives without one, when none lacks it)
    const textures = materialTextures(m.material).map((t) => `${t.key}: ${t.texture.image}`);
    const label = m.name || `material ${k + 1}`;
    folder.add({ value: textures.length ? textures.join(', ') : 'no textures' }, 'value').name(label).disable();
  });
  folder.add({ one: () => setMaterial(principledDefault()) }, 'one').name('one material for all');
}

/** The principled material with every input at its default. */
export function principledDefault(): Material {
  return normalizeMaterial(materialSchema('principled')!.parse({ type: 'principled' }) as Record<string, unknown>);
}

// ---------------------------------------------------------------- examples

/** The files the mesh examples name (the bunny as a PLY with smooth normals). */
export async function meshExampleFiles(): Promise<Map<string, Blob>> {
  const { default: bunny } = await import('bunny');
  const positions = Float32Array.from(bunny.positions.flat());
  const indices = Uint32Array.from(bunny.cells.flat());
  const ply = encodePly({ positions, indices, normals: vertexNormals(positions, indices) });
  return new Map([['bunny.ply', new Blob([ply as BlobPart], { type: 'application/octet-stream' })]]);
}

/** Area-weighted vertex normals (the package has none; flat facets at 3.7k triangles look faceted). */
export function vertexNormals(p: Float32Array, indices: Uint32Array): Float32Array {
  const n = new Float32Array(p.length);
  for (let t = 0; t < indices.length; t += 3) {
    const [a, b, c] = [indices[t] * 3, indices[t + 1] * 3, indices[t + 2] * 3];
    const e1 = [p[b] - p[a], p[b + 1] - p[a + 1], p[b + 2] - p[a + 2]];
    const e2 = [p[c] - p[a], p[c + 1] - p[a + 1], p[c + 2] - p[a + 2]];
    const cross = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
    for (const v of [a, b, c]) for (let k = 0; k < 3; k++) n[v + k] += cross[k];
  }
  for (let v = 0; v < n.length; v += 3) {
    const length = Math.hypot(n[v], n[v + 1], n[v + 2]) || 1;
    for (let k = 0; k < 3; k++) n[v + k] /= length;
  }
  return n;
}
