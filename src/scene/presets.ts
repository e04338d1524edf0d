/**
 * Example scenes bundled with the library and the page. They are copies of
 * test/fixtures/scenes/*.json (src must not depend on test/); the schema unit
 * test checks that the two stay identical.
 */
import emissive from './presets/emissive.json';
import furnace from './presets/furnace.json';
import glass from './presets/glass.json';
import glossy from './presets/glossy.json';
import mirrors from './presets/mirrors.json';
import seed from './presets/seed.json';
import smallLight from './presets/small-light.json';
import { parseScene } from './schema';
import type { Scene } from './types';

/** Scene JSON by name, deep-frozen: parse it (`parseScene`) to get an editable `Scene`. */
export const PRESETS: Readonly<Record<string, unknown>> = deepFreeze({
  seed,
  glossy,
  mirrors,
  'small-light': smallLight,
  glass,
  emissive,
  furnace,
});

/** Preset names in display order. */
export const PRESET_NAMES: readonly string[] = Object.freeze(Object.keys(PRESETS));

/** The project's default scene (the "seed" preset, 256 x 192), as JSON. */
export const DEFAULT_SCENE_JSON: unknown = PRESETS.seed;

/** The default scene, parsed: a fresh object on every call. */
export function defaultScene(): Scene {
  return parseScene(DEFAULT_SCENE_JSON);
}

function deepFreeze<T>(value: T): T {
  if (typeof value === 'object' && value !== null && !Object.isFrozen(value)) {
    Object.freeze(value);
    for (const child of Object.values(value)) deepFreeze(child);
  }
  return value;
}
