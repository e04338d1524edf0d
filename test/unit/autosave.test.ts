/**
 * The autosave's status must never say "saved" while a change is still
 * unsaved: the page tests (and a user closing the tab) rely on it. The race:
 * a save is writing when a new edit is finished; the write of the older
 * state completes after that edit. Storage is a stub here; the App is the
 * few fields the autosave reads.
 */
import { afterEach, beforeEach, describe, expect, it, vi } from 'vitest';
import { defaultScene } from '../../src/scene/presets';
import { History } from '../../src/app/history';
import type { Scene } from '../../src/scene/types';

const writes: { text: string; finish: () => void }[] = [];
vi.mock('../../src/app/store', () => ({
  writeState: (text: string) => new Promise((resolve) => writes.push({ text, finish: () => resolve({ ok: true, value: undefined }) })),
  readState: vi.fn(),
  deleteState: vi.fn(),
  loadAsset: vi.fn(),
  pruneAssets: vi.fn(),
  saveAsset: vi.fn(),
}));

const { Autosave } = await import('../../src/app/persistence');

function fakeApp() {
  const scene = defaultScene();
  return {
    scene,
    homeView: scene.camera,
    view: { exposure: 0, toneMap: 'aces', paused: false, targetSpp: 0, denoise: false },
    history: new History<Scene>(),
  };
}

describe('autosave status', () => {
  beforeEach(() => {
    vi.useFakeTimers();
    vi.stubGlobal('window', globalThis);
    writes.length = 0;
  });
  afterEach(() => {
    vi.useRealTimers();
    vi.unstubAllGlobals();
  });

  it('stays pending when a change comes in while an older state is being written, and then saves it', async () => {
    const app = fakeApp();
    const statuses: string[] = [];
    const autosave = new Autosave(app as never, (status) => statuses.push(status), 100);
    autosave.schedule();
    await vi.advanceTimersByTimeAsync(100); // the first save starts writing
    expect(writes).toHaveLength(1);
    app.history.record(structuredClone(app.scene)); // an edit finishes during the write
    app.scene.camera.fov += 5;
    autosave.schedule();
    writes[0].finish();
    await vi.advanceTimersByTimeAsync(0);
    expect(autosave.status, 'the older write must not report the newer change saved').toBe('pending');
    await vi.advanceTimersByTimeAsync(100); // the debounced second save
    expect(writes).toHaveLength(2);
    expect(JSON.parse(writes[1].text).undo).toHaveLength(1);
    writes[1].finish();
    await vi.advanceTimersByTimeAsync(0);
    expect(autosave.status).toBe('saved');
  });

  it('reports saved when nothing changed during the write', async () => {
    const app = fakeApp();
    const autosave = new Autosave(app as never, () => {}, 100);
    autosave.schedule();
    expect(autosave.status).toBe('pending');
    await vi.advanceTimersByTimeAsync(100);
    writes[0].finish();
    await vi.advanceTimersByTimeAsync(0);
    expect(autosave.status).toBe('saved');
  });
});
