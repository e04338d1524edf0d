/**
 * The scene's selectable objects by name, for the panel's object list, the
 * selection folder's title and the sun markers' accessible names: "light 3:
 * spot", "sphere 1", "mesh 2: bunny.obj". Numbers count from 1 within
 * `lights`, `spheres` and `meshes` (the scene file's order, as the folder
 * title always said); a light also says its kind, since lights are told
 * apart by kind first. Pure: no DOM.
 */
import { lightLabel } from '../lights/registry';
import type { Scene } from '../scene/types';
import type { Selection } from './App';

export interface SceneObject {
  selection: Selection;
  label: string;
  /** What the object list's option holds: `kind:index` (`selectionKey`). */
  key: string;
}

/** A selection as a string (the list's value): `kind:index`, or '' for none. */
export const selectionKey = (selection: Selection | null): string => (selection ? `${selection.kind}:${selection.index}` : '');

/** The object's name ("light 3: spot", "sphere 1", "mesh 2: bunny.obj"), or null when the scene has no such object. */
export function objectLabel(scene: Scene, { kind, index }: Selection): string | null {
  const number = `${kind} ${index + 1}`;
  if (kind === 'light') {
    const light = scene.lights[index];
    return light ? `${number}: ${lightLabel(light.type)}` : null;
  }
  if (kind === 'sphere') return scene.spheres[index] ? number : null;
  const mesh = scene.meshes[index];
  return mesh ? `${number}: ${mesh.file.split('/').pop()}` : null;
}

/** Every object of the scene, lights first (the ones hardest to click), then spheres, then meshes. */
export function sceneObjects(scene: Scene): SceneObject[] {
  const all = [
    ...scene.lights.map((_, index): Selection => ({ kind: 'light', index })),
    ...scene.spheres.map((_, index): Selection => ({ kind: 'sphere', index })),
    ...scene.meshes.map((_, index): Selection => ({ kind: 'mesh', index })),
  ];
  return all.map((selection) => ({ selection, label: objectLabel(scene, selection)!, key: selectionKey(selection) }));
}

/** The object a list value names, or null (none, or no longer in the scene). */
export function objectOfKey(scene: Scene, key: string): Selection | null {
  return sceneObjects(scene).find((o) => o.key === key)?.selection ?? null;
}
