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
import { defaultMaterial } from '../materials/registry';
import { MAX_MESHES } from '../scene/limits';
import { formatIssue } from '../scene/schema';
import { encodePly, MESH_EXTENSIONS } from '../scene/mesh';
import { decodeMeshOffThread } from './meshDecode';
import type { Material, Mesh, TriangleMesh, Vec3 } from '../scene/types';
import type { App } from './App';
import { addSphereMaterialControls, type TextureSlots } from './materialControls';
import { fitMesh, frameCamera, worldBoundingSphere } from './meshFit';
import { clearError, showError } from './messages';
import type { CompanionFiles } from './sceneLoader';

export const isModelFile = (name: string) => MESH_EXTENSIONS.some((ext) => name.toLowerCase().endsWith(ext));

/** Keeps the user's file with the autosave (Autosave.keepFiles). */
export type KeepFiles = (files: CompanionFiles) => void;

/**
 * Adds a model file to the scene as a new mesh, fitted and framed, as one
 * undoable edit, and selects it. Returns whether it was added; on failure an
 * issue naming `meshes[i].file` is shown and nothing changes.
 */
export async function addModelFile(app: App, file: File, keep: KeepFiles): Promise<boolean> {
  const fail = (message: string) => {
    const issue = { path: `meshes[${app.scene.meshes.length}].file`, message: `${JSON.stringify(file.name)}: ${message}` };
    showError(`The model "${file.name}" could not be added; the scene is unchanged.`, [formatIssue(issue)]);
    return false;
  };
  if (app.scene.meshes.length >= MAX_MESHES) return fail(`the scene already has ${MAX_MESHES} meshes, the most it can hold`);
  let data: TriangleMesh;
  try {
    data = await decodeMeshOffThread(new Uint8Array(await file.arrayBuffer()), file.name);
  } catch (error) {
    return fail(error instanceof AssetError ? error.message : `cannot be read (${(error as Error)?.message ?? String(error)})`);
  }
  const name = fileNameFor(app, file.name, data);
  data = app.assets.meshes.get(name) ?? data;
  const mesh: Mesh = { file: name, material: { ...defaultMaterial(), roughness: 0.5 }, ...fitMesh(data, file.name, app.scene) };
  // A model already in the scene is stored once more only if it cannot be instanced (src/render/bvh/groups.ts).
  const trianglesOf = (f: string) => ((f === name ? data : app.assets.meshes.get(f))?.indices.length ?? 0) / 3;
  const triangles = storedTriangles({ ...app.scene, meshes: [...app.scene.meshes, mesh] }, trianglesOf);
  if (triangles > MAX_TRIANGLES) return fail(`the scene's meshes would have ${triangles} triangles; the most is ${MAX_TRIANGLES}`);
  const bounds = worldBoundingSphere(mesh, data);
  const camera = frameCamera(app.scene.camera, bounds.center, bounds.radius, app.aspect);
  clearError();
  app.addAssets({ maps: new Map(), meshes: new Map([[name, data]]) });
  app.edit((s) => {
    s.version = 2;
    s.meshes.push(mesh);
    s.camera = camera;
  });
  app.select({ kind: 'mesh', index: app.scene.meshes.length - 1 });
  keep(new Map([[name, file]]));
  return true;
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
