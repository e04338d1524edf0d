/**
 * The page's autosaved state as one JSON text: the scene (with its camera),
 * the "reset view" camera, the panel's view settings and the undo history.
 * Pure: encoding trims the history to a budget, decoding validates everything
 * with the one scene parser and never throws. Anything it cannot trust is
 * reported (`reason`) and the caller discards it.
 */
import { z } from 'zod';
import { TONEMAPS, type ToneMap } from '../render/toneMaps';
import { formatIssue, safeParseScene } from '../scene/schema';
import { serializeScene } from '../scene/serialize';
import type { Camera, Scene } from '../scene/types';

export const SAVED_FORMAT = 'pathtrace-autosave';
export const SAVED_VERSION = 1;
/** A saved record longer than this (UTF-16 units of JSON) is not ours: discarded unread. */
export const MAX_SAVED_CHARS = 8_000_000;
/**
 * The undo and redo stacks are saved while they fit in this many characters
 * of JSON (the newest steps are kept); with a scene of at most
 * MAX_SCENE_BYTES the record stays under MAX_SAVED_CHARS.
 */
export const HISTORY_BUDGET_CHARS = 4_000_000;

export interface SavedView {
  exposure: number;
  toneMap: ToneMap;
  targetSpp: number;
  /** The "Denoise" toggle (records saved before it existed lack it: off). */
  denoise: boolean;
}

export interface SavedState {
  scene: Scene;
  homeCamera: Camera;
  view: SavedView;
  undo: Scene[];
  redo: Scene[];
  /** Digest of the share link this state came from: reloading that link keeps the edits made since. */
  linkDigest: string | null;
  /** Keys of the user's own files (models, maps) stored beside the record (assetStore.ts). */
  assets: string[];
}

export type DecodeResult =
  | { ok: true; state: SavedState; notes: string[] }
  | { ok: false; reason: string };

const envelope = z.object({
  format: z.literal(SAVED_FORMAT),
  version: z.literal(SAVED_VERSION),
  savedAt: z.number(),
  scene: z.unknown(),
  homeCamera: z.unknown(),
  view: z.object({
    exposure: z.number().finite().min(-20).max(20),
    toneMap: z.enum(TONEMAPS),
    targetSpp: z.number().int().min(0).max(1e9),
    denoise: z.boolean().default(false),
  }),
  undo: z.array(z.unknown()),
  redo: z.array(z.unknown()),
  linkDigest: z.string().max(64).nullable(),
  assets: z.array(z.string().max(200)).max(1000),
});

/** The record to store, and how many history steps did not fit. */
export function encodeState(state: SavedState, savedAt = Date.now()): { text: string; droppedSteps: number } {
  const json = (scenes: Scene[]) => scenes.map((s) => JSON.stringify(serializeScene(s)));
  const undo = json(state.undo);
  const redo = json(state.redo);
  let size = [...undo, ...redo].reduce((sum, text) => sum + text.length + 1, 0);
  let droppedSteps = 0;
  // Oldest undo steps go first, then the redo steps furthest away.
  while (size > HISTORY_BUDGET_CHARS && (undo.length || redo.length)) {
    size -= (undo.length ? undo.shift()! : redo.shift()!).length + 1;
    droppedSteps++;
  }
  const homeCamera = serializeScene({ ...state.scene, camera: state.homeCamera }).camera;
  const head = JSON.stringify({
    format: SAVED_FORMAT,
    version: SAVED_VERSION,
    savedAt,
    scene: serializeScene(state.scene),
    homeCamera,
    view: { exposure: state.view.exposure, toneMap: state.view.toneMap, targetSpp: state.view.targetSpp, denoise: state.view.denoise },
    linkDigest: state.linkDigest,
    assets: state.assets,
  });
  // The history's scenes are already JSON: splice them in instead of serializing twice.
  const text = `${head.slice(0, -1)},"undo":[${undo.join(',')}],"redo":[${redo.join(',')}]}`;
  return { text, droppedSteps };
}

/** Validates a stored record. Never throws. */
export function decodeState(record: unknown): DecodeResult {
  if (typeof record !== 'string') return { ok: false, reason: 'it is not text' };
  if (record.length > MAX_SAVED_CHARS) return { ok: false, reason: `it is ${record.length} characters long; at most ${MAX_SAVED_CHARS} are read` };
  let value: unknown;
  try {
    value = JSON.parse(record);
  } catch (error) {
    return { ok: false, reason: `it is not valid JSON (${(error as Error).message})` };
  }
  const parsed = envelope.safeParse(value);
  if (!parsed.success) {
    const issue = parsed.error.issues[0];
    return { ok: false, reason: `${issue.path.join('.') || 'the record'}: ${issue.message}` };
  }
  const data = parsed.data;
  const scene = safeParseScene(data.scene);
  if (!scene.ok) return { ok: false, reason: `its scene is not valid (${scene.issues.slice(0, 3).map(formatIssue).join('; ')})` };
  const notes: string[] = [];
  const home = safeParseScene({ ...(data.scene as object), camera: data.homeCamera });
  const homeCamera = home.ok ? home.scene.camera : structuredClone(scene.scene.camera);
  if (!home.ok) notes.push('the saved "reset view" camera was not valid and was replaced by the current camera');
  const history = decodeHistory(data.undo, data.redo);
  if (!history) notes.push('the saved undo history was not valid and was discarded');
  return {
    ok: true,
    notes,
    state: {
      scene: scene.scene,
      homeCamera,
      view: data.view,
      undo: history?.undo ?? [],
      redo: history?.redo ?? [],
      linkDigest: data.linkDigest,
      assets: data.assets,
    },
  };
}

function decodeHistory(undo: unknown[], redo: unknown[]): { undo: Scene[]; redo: Scene[] } | null {
  const scenes = (list: unknown[]) => {
    const out: Scene[] = [];
    for (const item of list) {
      const result = safeParseScene(item);
      if (!result.ok) return null;
      out.push(result.scene);
    }
    return out;
  };
  const u = scenes(undo);
  const r = scenes(redo);
  return u && r ? { undo: u, redo: r } : null;
}

/** A short, stable digest of a share link's hash (cyrb53): not security, only identity. */
export function linkDigest(text: string): string {
  let h1 = 0xdeadbeef;
  let h2 = 0x41c6ce57;
  for (let i = 0; i < text.length; i++) {
    const c = text.charCodeAt(i);
    h1 = Math.imul(h1 ^ c, 2654435761);
    h2 = Math.imul(h2 ^ c, 1597334677);
  }
  h1 = Math.imul(h1 ^ (h1 >>> 16), 2246822507) ^ Math.imul(h2 ^ (h2 >>> 13), 3266489909);
  h2 = Math.imul(h2 ^ (h2 >>> 16), 2246822507) ^ Math.imul(h1 ^ (h1 >>> 13), 3266489909);
  return `${text.length.toString(36)}-${(h2 >>> 0).toString(36)}${(h1 >>> 0).toString(36)}`;
}
