/**
 * The autosave record (src/app/savedState.ts): what is encoded comes back
 * the same; the undo history is trimmed (oldest first) to its budget; any
 * record that cannot be trusted is refused with a reason and never throws.
 */
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { History } from '../../src/app/history';
import {
  decodeState,
  encodeState,
  HISTORY_BUDGET_CHARS,
  linkDigest,
  MAX_SAVED_CHARS,
  type SavedState,
} from '../../src/app/savedState';
import { defaultScene, PRESETS } from '../../src/scene/presets';
import { parseScene } from '../../src/scene/schema';
import { serializeScene } from '../../src/scene/serialize';
import type { Scene } from '../../src/scene/types';

function state(overrides: Partial<SavedState> = {}): SavedState {
  const scene = defaultScene();
  (scene.spheres[0].material as { color: [number, number, number] }).color = [0.1, 0.7, 0.2];
  return {
    scene,
    homeCamera: defaultScene().camera,
    view: { exposure: 1.5, toneMap: 'agx', targetSpp: 64, denoise: true },
    undo: [defaultScene(), parseScene(PRESETS.glossy)],
    redo: [parseScene(PRESETS.mirrors)],
    linkDigest: linkDigest('#scene=abc'),
    assets: [],
    ...overrides,
  };
}

const json = (scenes: Scene[]) => scenes.map(serializeScene);

describe('saved state', () => {
  it('round-trips the scene, home camera, view settings, history and link', () => {
    const original = state();
    const { text, droppedSteps } = encodeState(original);
    expect(droppedSteps).toBe(0);
    const decoded = decodeState(text);
    if (!decoded.ok) throw new Error(decoded.reason);
    expect(decoded.notes).toEqual([]);
    expect(serializeScene(decoded.state.scene)).toEqual(serializeScene(original.scene));
    expect(decoded.state.homeCamera).toEqual(original.homeCamera);
    expect(decoded.state.view).toEqual(original.view);
    expect(json(decoded.state.undo)).toEqual(json(original.undo));
    expect(json(decoded.state.redo)).toEqual(json(original.redo));
    expect(decoded.state.linkDigest).toBe(original.linkDigest);
  });

  it('reads a record saved before the Denoise toggle existed with the toggle off', () => {
    const record = JSON.parse(encodeState(state()).text);
    delete record.view.denoise;
    const decoded = decodeState(JSON.stringify(record));
    if (!decoded.ok) throw new Error(decoded.reason);
    expect(decoded.state.view).toEqual({ exposure: 1.5, toneMap: 'agx', targetSpp: 64, denoise: false });
  });

  it('keeps the newest undo steps that fit the history budget', () => {
    const big = defaultScene();
    const entry = JSON.stringify(serializeScene(big)).length + 1;
    const count = Math.ceil(HISTORY_BUDGET_CHARS / entry) + 5;
    const undo = Array.from({ length: count }, (_, i) => {
      const s = defaultScene();
      s.camera.fov = 10 + (i % 100);
      return s;
    });
    const { text, droppedSteps } = encodeState(state({ undo, redo: [] }));
    expect(droppedSteps).toBeGreaterThanOrEqual(5);
    expect(text.length).toBeLessThanOrEqual(MAX_SAVED_CHARS);
    const decoded = decodeState(text);
    if (!decoded.ok) throw new Error(decoded.reason);
    expect(decoded.state.undo.length).toBe(count - droppedSteps);
    expect(decoded.state.undo.at(-1)!.camera.fov).toBe(undo.at(-1)!.camera.fov); // the newest are kept
  });

  it('works with History: entries() saved, replace() restored', () => {
    const history = new History<number>(3);
    [1, 2, 3, 4].forEach((n) => history.record(n));
    expect(history.entries()).toEqual({ undo: [2, 3, 4], redo: [] });
    const restored = new History<number>(3);
    restored.replace([0, 1, 2, 3, 4], [9]);
    expect(restored.entries()).toEqual({ undo: [2, 3, 4], redo: [9] });
    expect(restored.undo(5)).toBe(4);
    expect(restored.redo(4)).toBe(5);
  });

  it('refuses what it cannot trust, with a reason', () => {
    const good = JSON.parse(encodeState(state()).text);
    const cases: [unknown, RegExp][] = [
      [undefined, /not text/],
      [{ scene: {} }, /not text/],
      ['{"format": ', /not valid JSON/],
      ['x'.repeat(MAX_SAVED_CHARS + 1), /characters long/],
      [JSON.stringify({ ...good, format: 'other' }), /format/],
      [JSON.stringify({ ...good, version: 99 }), /version/],
      [JSON.stringify({ ...good, view: { ...good.view, toneMap: 'sepia' } }), /view\.toneMap/],
      [JSON.stringify({ ...good, scene: { ...good.scene, camera: { ...good.scene.camera, fov: 'wide' } } }), /camera\.fov/],
      [JSON.stringify({ ...good, scene: null }), /scene is not valid/],
    ];
    for (const [record, reason] of cases) {
      const decoded = decodeState(record);
      expect(decoded.ok, String(record).slice(0, 40)).toBe(false);
      if (!decoded.ok) expect(decoded.reason).toMatch(reason);
    }
  });

  it('drops only a bad history or home camera, with a note', () => {
    const good = JSON.parse(encodeState(state()).text);
    const badHistory = decodeState(JSON.stringify({ ...good, undo: [...good.undo, { camera: 1 }] }));
    expect(badHistory.ok && badHistory.state.undo).toEqual([]);
    expect(badHistory.ok && badHistory.notes.join()).toMatch(/undo history/);
    const badHome = decodeState(JSON.stringify({ ...good, homeCamera: { fov: -1 } }));
    expect(badHome.ok && badHome.state.homeCamera).toEqual(state().scene.camera);
    expect(badHome.ok && badHome.notes.join()).toMatch(/reset view/);
  });

  it('never throws on arbitrary records', () => {
    fc.assert(
      fc.property(fc.oneof(fc.string(), fc.json(), fc.anything()), (record) => {
        const decoded = decodeState(record);
        expect(typeof decoded.ok).toBe('boolean');
      }),
      { numRuns: 300 },
    );
  });

  it('digests share links stably and distinctly', () => {
    expect(linkDigest('#scene=abc')).toBe(linkDigest('#scene=abc'));
    expect(linkDigest('#scene=abc')).not.toBe(linkDigest('#scene=abd'));
  });
});
