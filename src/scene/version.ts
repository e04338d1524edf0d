/**
 * Version 2 of the scene format is a superset of version 1: a document must
 * say `"version": 2` to use any key that version 2 adds. `versionIssues`
 * finds those keys in a document that does not (one issue per key, naming
 * its path); `requiredVersion` is the version a normalized scene needs.
 */
import type { SceneIssue } from './issues';
import type { Material, Scene } from './types';

const V2_MATERIAL_KEYS = ['type', 'emission', 'ior'];
const NEEDS_V2 = 'requires "version": 2';

export function versionIssues(input: unknown): SceneIssue[] {
  if (!isRecord(input) || input.version === 2) return [];
  if (input.version !== undefined && input.version !== 1) return [];
  const issues: SceneIssue[] = [];
  const materialKeys = (material: unknown, path: string) => {
    if (!isRecord(material)) return;
    for (const key of V2_MATERIAL_KEYS) if (key in material) issues.push({ path: `${path}.${key}`, message: NEEDS_V2 });
  };
  if ('meshes' in input) issues.push({ path: 'meshes', message: NEEDS_V2 });
  const environment = input.environment;
  if (isRecord(environment)) {
    for (const key of ['map', 'rotation']) if (key in environment) issues.push({ path: `environment.${key}`, message: NEEDS_V2 });
  }
  if (isRecord(input.ground)) materialKeys(input.ground.material, 'ground.material');
  if (Array.isArray(input.spheres)) {
    input.spheres.slice(0, 1000).forEach((sphere, i) => isRecord(sphere) && materialKeys(sphere.material, `spheres[${i}].material`));
  }
  return issues;
}

/** 2 when the scene uses anything version 1 cannot say, else 1. */
export function requiredVersion(scene: Scene): 1 | 2 {
  const v2Material = (m: Material) => m.type !== 'standard' || m.emission !== undefined;
  const usesV2 =
    scene.meshes.length > 0 ||
    (scene.environment !== null && 'map' in scene.environment) ||
    (scene.ground !== null && v2Material(scene.ground.material)) ||
    scene.spheres.some((sphere) => v2Material(sphere.material));
  return usesV2 ? 2 : 1;
}

function isRecord(value: unknown): value is Record<string, unknown> {
  return typeof value === 'object' && value !== null && !Array.isArray(value);
}
