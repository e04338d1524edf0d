/**
 * Autosave and restore of the page's work. Every change (a finished edit, a
 * load, undo, a panel setting) schedules a save, debounced; leaving the page
 * saves at once. Closing or reloading while something could not be saved
 * (storage full or missing, a user file over its limit) asks first.
 *
 * At start: a share link in the URL wins over the saved state, but the saved
 * scene becomes the step before it in the undo history (one Undo away, and
 * saved again with it). Reloading the same link keeps the edits made since.
 * A saved state that cannot be trusted is discarded with a notice.
 */
import { mergeAssets, NO_ASSETS, type SceneAssets } from '../scene/assets';
import { formatIssue } from '../scene/schema';
import type { Scene } from '../scene/types';
import type { App } from './App';
import { sceneFromHash } from './files';
import { decodeState, encodeState, linkDigest, type SavedState } from './savedState';
import { baseName, resolveAssets, type CompanionFiles } from './sceneLoader';
import { userFiles } from './userFiles';
import { deleteState, loadAsset, pruneAssets, readState, saveAsset, writeState } from './store';
import type { SafeParseResult } from '../scene/schema';

/** Quiet time after the last change before saving. */
export const SAVE_DELAY_MS = 400;

export type SaveStatus = 'idle' | 'pending' | 'saved' | 'failed';

export class Autosave {
  status: SaveStatus = 'idle';
  detail = '';
  /** The share link the current work came from (see savedState.linkDigest). */
  linkDigest: string | null = null;
  /** Keys of stored user files the scene names (the mesh and map loaders add to it). */
  assets: string[] = [];
  /** Things that could not be saved, by name: while any is here, leaving the page asks first. */
  readonly unsaved = new Map<string, string>();
  private timer = 0;
  private lastText = '';
  private running: Promise<void> | null = null;
  private again = false;
  /** Counts schedule() calls: a save that finishes after a newer change must not report 'saved'. */
  private changes = 0;

  constructor(
    private readonly app: App,
    private readonly onStatus: (status: SaveStatus, detail: string) => void,
    private readonly delayMs = SAVE_DELAY_MS,
  ) {}

  /** Starts saving on changes and when the page is hidden or left. */
  start(): void {
    this.app.onChange(() => this.schedule());
    const leave = () => void this.flush();
    window.addEventListener('pagehide', leave);
    document.addEventListener('visibilitychange', () => document.visibilityState === 'hidden' && leave());
    window.addEventListener('beforeunload', (event) => {
      if (this.status === 'pending') void this.flush();
      if (!this.needsWarning) return;
      event.preventDefault();
      event.returnValue = ''; // older browsers need it set to show the prompt
    });
  }

  /** True while leaving the page would lose something. */
  get needsWarning(): boolean {
    return this.status === 'failed' || this.unsaved.size > 0;
  }

  schedule(): void {
    this.changes += 1;
    clearTimeout(this.timer);
    this.setStatus(this.status === 'failed' ? 'failed' : 'pending', this.detail);
    this.timer = window.setTimeout(() => void this.flush(), this.delayMs);
  }

  /** Saves now (or after the save in flight). */
  flush(): Promise<void> {
    clearTimeout(this.timer);
    if (this.running) {
      this.again = true;
      return this.running;
    }
    this.running = this.save().finally(() => {
      this.running = null;
      if (this.again) {
        this.again = false;
        void this.flush();
      }
    });
    return this.running;
  }

  private async save(): Promise<void> {
    const changes = this.changes;
    const { text, droppedSteps } = encodeState(this.currentState());
    // A change made while this save was writing is still to be saved (its timer is set): stay 'pending'.
    const settled = (status: SaveStatus, detail: string) => {
      if (this.changes === changes || status === 'failed') this.setStatus(status, detail);
    };
    if (text === this.lastText && this.status !== 'failed') {
      settled('saved', this.detail);
      return;
    }
    const result = await writeState(text);
    if (!result.ok) {
      settled('failed', `not saved: ${result.reason}`);
      return;
    }
    this.lastText = text;
    settled('saved', droppedSteps > 0 ? `saved (the oldest ${droppedSteps} undo steps did not fit)` : 'saved');
  }

  /**
   * Keeps the user's files a just-opened scene needs (by file name: those
   * it names, and the .bin, .mtl and images its models read beside them,
   * userFiles.ts), so the scene reopens after a reload. A file that cannot be kept (too large,
   * storage full) is listed in `unsaved`: leaving the page then asks first.
   */
  async keepFiles(scene: Scene, files: CompanionFiles): Promise<void> {
    for (const file of userFiles(scene, this.app.assets)) {
      const name = baseName(file);
      const blob = files.get(file) ?? files.get(name);
      if (!blob) continue; // already kept with an earlier scene
      const saved = await saveAsset(name, blob);
      if (saved.ok) {
        this.unsaved.delete(name);
        if (!this.assets.includes(name)) this.assets = [...this.assets, name];
      } else {
        this.unsaved.set(name, saved.reason);
      }
    }
    if (this.unsaved.size) this.setStatus(this.status, `not kept: ${[...this.unsaved.values()].join('; ')}`);
    this.schedule();
  }

  private currentState(): SavedState {
    const app = this.app;
    const { undo, redo } = app.history.entries();
    return { scene: app.scene, homeCamera: app.homeView, view: app.view, undo, redo, linkDigest: this.linkDigest, assets: this.assets };
  }

  private setStatus(status: SaveStatus, detail: string): void {
    this.status = status;
    this.detail = detail;
    this.onStatus(status, detail);
  }
}

// ---------------------------------------------------------------- start-up

export interface StartState {
  /** The saved state to restore first (possibly then replaced by a link's scene). */
  saved: SavedState | null;
  /** The scene from the URL's share link, to load over the saved state. */
  linkScene: Scene | null;
  linkDigest: string | null;
  /** The link's scene was rejected: its issues (the saved or default scene opens). */
  linkResult: SafeParseResult | null;
  /** The decoded files the saved scenes name. */
  assets: SceneAssets;
  /** Messages for the user (restored, discarded, recovered...). */
  notices: string[];
}

/** Reads the saved state and the URL's share link and decides what opens. Never throws. */
export async function readStartState(hash: string): Promise<StartState> {
  const notices: string[] = [];
  const stored = await readState();
  let saved: SavedState | null = null;
  if (!stored.ok) {
    notices.push(`The saved scene could not be read (${stored.reason}); changes will not be kept.`);
  } else if (stored.value !== undefined) {
    const decoded = decodeState(stored.value);
    if (decoded.ok) {
      saved = decoded.state;
      notices.push(...decoded.notes.map((note) => `Restored your last scene, but ${note}.`));
    } else {
      notices.push(`The saved scene was discarded because ${decoded.reason}; the example scene is open instead.`);
      await deleteState();
    }
  }
  let assets: SceneAssets = NO_ASSETS;
  if (saved) {
    const restored = await restoreFiles(saved);
    if (restored.ok) {
      assets = restored.assets;
      notices.push(...restored.notes);
    } else {
      notices.push(`The saved scene was discarded because ${restored.reason}; the example scene is open instead.`);
      saved = null;
    }
  }
  const link = sceneFromHash(hash);
  const digest = link ? linkDigest(hash) : null;
  if (link?.ok && saved && saved.linkDigest === digest) {
    // Reloading the link this work started from: keep the edits made since.
    return { saved, linkScene: null, linkDigest: digest, linkResult: null, assets, notices };
  }
  if (link?.ok) {
    if (saved) notices.push('Opened the scene in the link; your previous scene is one Undo away.');
    return { saved, linkScene: link.scene, linkDigest: digest, linkResult: null, assets, notices };
  }
  if (saved && !notices.length) notices.push('Restored your last scene.');
  return { saved, linkScene: null, linkDigest: saved?.linkDigest ?? null, linkResult: link, assets, notices };
}

/**
 * Decodes the stored files the saved scene and its history name. The scene
 * needs all of its files; a history step whose files are gone is dropped.
 */
async function restoreFiles(
  saved: SavedState,
): Promise<{ ok: true; assets: SceneAssets; notes: string[] } | { ok: false; reason: string }> {
  const files = new Map<string, Blob>();
  for (const name of saved.assets) {
    const blob = await loadAsset(name);
    if (blob.ok && blob.value) files.set(name, blob.value);
  }
  const scene = await resolveAssets(saved.scene, files);
  if (!scene.ok) return { ok: false, reason: `a file it names is not kept (${scene.issues.slice(0, 3).map(formatIssue).join('; ')})` };
  let assets = scene.assets;
  let dropped = 0;
  const usable = async (list: Scene[]) => {
    const out: Scene[] = [];
    for (const step of list) {
      const result = await resolveAssets(step, files, assets);
      if (result.ok) {
        assets = mergeAssets(assets, result.assets);
        out.push(step);
      } else dropped++;
    }
    return out;
  };
  saved.undo = await usable(saved.undo);
  saved.redo = await usable(saved.redo);
  void pruneAssets(saved.assets);
  const notes = dropped ? [`Restored your last scene, but ${dropped} undo steps named files that are no longer kept.`] : [];
  return { ok: true, assets, notes };
}
