/**
 * The page's persistent storage: one IndexedDB object store (through
 * idb-keyval) holding the autosave record and, later, the user's own files
 * (models, maps) that a scene names. IndexedDB, not localStorage: local
 * storage holds about 5 MB of strings, too little for the undo history and
 * for models and maps. Every call resolves to a result and never throws: a
 * browser without IndexedDB (some private modes) only loses persistence.
 *
 * Layout (tests write corrupt records here): database "pathtrace", object
 * store "keyval", key "autosave" (a JSON string, savedState.ts) and keys
 * "asset:<name>" (Blobs).
 */
import { createStore, del, get, keys, set, type UseStore } from 'idb-keyval';

export const DB_NAME = 'pathtrace';
export const STORE_NAME = 'keyval';
export const STATE_KEY = 'autosave';
const ASSET_PREFIX = 'asset:';

import { MAX_ASSET_BYTES, MAX_TOTAL_ASSET_BYTES } from './fileLimits';

export { MAX_ASSET_BYTES, MAX_TOTAL_ASSET_BYTES };

export type StoreResult<T = void> = { ok: true; value: T } | { ok: false; reason: string };

let store: UseStore | null = null;
function db(): UseStore {
  store ??= createStore(DB_NAME, STORE_NAME);
  return store;
}

async function attempt<T>(action: () => Promise<T>): Promise<StoreResult<T>> {
  try {
    if (typeof indexedDB === 'undefined') return { ok: false, reason: 'this browser has no IndexedDB' };
    return { ok: true, value: await action() };
  } catch (error) {
    const e = error as Error;
    return { ok: false, reason: e?.name === 'QuotaExceededError' ? 'the browser storage is full' : (e?.message ?? String(error)) };
  }
}

export const readState = () => attempt(() => get<unknown>(STATE_KEY, db()));
export const writeState = (text: string) => attempt(() => set(STATE_KEY, text, db()));
export const deleteState = () => attempt(() => del(STATE_KEY, db()));

// ---------------------------------------------------------------- the user's own files

/**
 * Stores a user file (a model or a map the scene names) so the scene reopens
 * with it. The hook for the mesh and environment-map loaders: they call this
 * after a successful load, and list `name` in the saved state's `assets`.
 * Fails (without storing) over MAX_ASSET_BYTES or MAX_TOTAL_ASSET_BYTES;
 * the caller then keeps the page's beforeunload warning armed (Autosave.unsaved).
 */
export async function saveAsset(name: string, blob: Blob): Promise<StoreResult> {
  if (blob.size > MAX_ASSET_BYTES) return { ok: false, reason: `${name} is ${blob.size} bytes; at most ${MAX_ASSET_BYTES} are kept` };
  const total = await assetBytes(name);
  if (!total.ok) return total;
  if (total.value + blob.size > MAX_TOTAL_ASSET_BYTES) {
    return { ok: false, reason: `keeping ${name} would take the saved files over ${MAX_TOTAL_ASSET_BYTES} bytes` };
  }
  const stored = await attempt(() => set(ASSET_PREFIX + name, blob, db()));
  return stored.ok ? { ok: true, value: undefined } : stored;
}

export const loadAsset = (name: string) => attempt(() => get<Blob>(ASSET_PREFIX + name, db()));

/** Deletes stored files the saved scene no longer names. */
export async function pruneAssets(keep: readonly string[]): Promise<StoreResult> {
  return attempt(async () => {
    const wanted = new Set(keep.map((name) => ASSET_PREFIX + name));
    for (const key of await keys<string>(db())) {
      if (typeof key === 'string' && key.startsWith(ASSET_PREFIX) && !wanted.has(key)) await del(key, db());
    }
  });
}

/** Bytes of the stored files other than `except`. */
async function assetBytes(except: string): Promise<StoreResult<number>> {
  return attempt(async () => {
    let total = 0;
    for (const key of await keys<string>(db())) {
      if (typeof key !== 'string' || !key.startsWith(ASSET_PREFIX) || key === ASSET_PREFIX + except) continue;
      const blob = await get<Blob>(key, db());
      total += blob?.size ?? 0;
    }
    return total;
  });
}
