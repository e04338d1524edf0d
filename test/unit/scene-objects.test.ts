/**
 * The scene's objects by name (src/app/sceneObjects.ts): the panel's object
 * list, the selection folder's title and the sun markers' names.
 */
import { describe, expect, it } from 'vitest';
import { createLight } from '../../src/lights/registry';
import { defaultScene } from '../../src/scene/presets';
import type { Scene } from '../../src/scene/types';
import { objectLabel, objectOfKey, sceneObjects, selectionKey } from '../../src/app/sceneObjects';

function scene(): Scene {
  const s = defaultScene();
  s.lights = [createLight('spot', [0, 0, 0]), createLight('rectangle', [0, 0, 0]), createLight('directional', [0, 0, 0])];
  s.spheres = s.spheres.slice(0, 2);
  const mesh = { file: 'models/bunny.obj', material: null, position: [0, 0, 0], rotation: [0, 0, 0], scale: [1, 1, 1] } as Scene['meshes'][number];
  s.meshes = [mesh];
  return s;
}

describe('scene objects', () => {
  it('lists every light (by index and kind), then the spheres, then the meshes (by file name)', () => {
    expect(sceneObjects(scene()).map((o) => o.label)).toEqual([
      'light 1: spot',
      'light 2: rectangle',
      'light 3: directional',
      'sphere 1',
      'sphere 2',
      'mesh 1: bunny.obj',
    ]);
  });

  it('gives each a distinct key that names it back', () => {
    const s = scene();
    const objects = sceneObjects(s);
    expect(new Set(objects.map((o) => o.key)).size).toBe(objects.length);
    for (const o of objects) {
      expect(o.key).toBe(selectionKey(o.selection));
      expect(objectOfKey(s, o.key)).toEqual(o.selection);
      expect(objectLabel(s, o.selection)).toBe(o.label);
    }
    expect(objectOfKey(s, 'light:2')).toEqual({ kind: 'light', index: 2 });
  });

  it('names none for no selection, and nothing for an object the scene no longer has', () => {
    const s = scene();
    expect(selectionKey(null)).toBe('');
    expect(objectOfKey(s, '')).toBeNull();
    expect(objectOfKey(s, 'light:3')).toBeNull();
    expect(objectOfKey(s, 'sphere:-1')).toBeNull();
    expect(objectOfKey(s, 'bogus')).toBeNull();
    expect(objectLabel(s, { kind: 'mesh', index: 1 })).toBeNull();
    s.lights.pop();
    expect(objectOfKey(s, 'light:2'), 'removed (undo, delete)').toBeNull();
  });
});
