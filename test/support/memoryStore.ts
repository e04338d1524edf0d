/**
 * An in-memory stand-in for the page's IndexedDB store (src/app/store.ts),
 * for unit tests of autosave: `vi.mock('../../src/app/store', () =>
 * import('../support/memoryStore'))`, then read `stored` (the state under
 * 'autosave', each asset under 'asset:NAME').
 */
export const stored = new Map<string, unknown>();

export const writeState = async (text: string) => (stored.set('autosave', text), { ok: true, value: undefined });
export const readState = async () => ({ ok: true, value: stored.get('autosave') });
export const deleteState = async () => ({ ok: true, value: undefined });
export const saveAsset = async (name: string, blob: Blob) => (stored.set(`asset:${name}`, blob), { ok: true, value: undefined });
export const loadAsset = async (name: string) => ({ ok: true, value: stored.get(`asset:${name}`) });
export const pruneAssets = async () => ({ ok: true, value: undefined });
