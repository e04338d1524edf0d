/** Helpers of the light kinds' unit tests (src/lights/<kind>/<kind>.test.ts). */
import { safeParseScene } from '../../src/scene/schema';
import type { Scene } from '../../src/scene/types';
import { parseScene } from '../../src/scene/schema';

const camera = { position: [0, 1, 5], target: [0, 0, 0] };

/** A version-3 scene JSON with these lights. */
export const sceneWith = (lights: unknown[], version = 3) => ({ version, camera, lights });
/** The one light of a parsed scene. */
export const parseLight = (light: unknown, version = 3) => parseScene(sceneWith([light], version)).lights[0];
/** "path: message" of each problem of a scene with this one light. */
export function problems(light: unknown, version = 3): string[] {
  const result = safeParseScene(sceneWith([light], version));
  return result.ok ? [] : result.issues.map((i) => `${i.path}: ${i.message}`);
}
export type { Scene };
