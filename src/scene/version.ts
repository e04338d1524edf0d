/**
 * Each version of the scene format is a superset of the one before: a
 * document must say `"version": N` to use any key (or material kind) that
 * version N adds. `versionIssues` finds those in a document that does not
 * (one issue per key, naming its path); `requiredVersion` is the version a
 * normalized scene needs. Material kinds say which version brought them
 * (src/materials/<kind>/kind.ts).
 */
import { lightVersion } from '../lights/registry';
import { materialVersion, typeVersion } from '../materials/registry';
import type { SceneIssue } from './issues';
import type { Scene } from './types';

/** Keys of any material that version 2 brought (`ior`: of its glass, on a material without `type` in version 1). */
const V2_MATERIAL_KEYS = ['type', 'emission', 'ior'];
const needs = (version: number) => `requires "version": ${version}`;

export function versionIssues(input: unknown): SceneIssue[] {
  if (!isRecord(input)) return [];
  const declared = input.version === undefined ? 1 : input.version;
  if (declared !== 1 && declared !== 2) return [];
  const issues: SceneIssue[] = [];
  const require = (version: number, path: string) => {
    if (version > declared) issues.push({ path, message: needs(version) });
  };
  // A kind's `type` needs its kind's version (at least 2: version 1 has no `type`).
  const materialKeys = (material: unknown, path: string) => {
    if (!isRecord(material)) return;
    for (const key of V2_MATERIAL_KEYS) if (key in material) require(key === 'type' ? Math.max(2, typeVersion(material.type) ?? 2) : 2, `${path}.${key}`);
  };
  if ('meshes' in input) require(2, 'meshes');
  // A light's `type` (every kind but the sphere) came with version 3.
  if (Array.isArray(input.lights)) {
    input.lights.slice(0, 1000).forEach((light, i) => isRecord(light) && 'type' in light && require(3, `lights[${i}].type`));
  }
  const environment = input.environment;
  if (isRecord(environment)) {
    for (const key of ['map', 'rotation']) if (key in environment) require(2, `environment.${key}`);
  }
  if (isRecord(input.ground)) materialKeys(input.ground.material, 'ground.material');
  if (Array.isArray(input.spheres)) {
    input.spheres.slice(0, 1000).forEach((sphere, i) => isRecord(sphere) && materialKeys(sphere.material, `spheres[${i}].material`));
  }
  if (Array.isArray(input.meshes)) {
    input.meshes.slice(0, 1000).forEach((mesh, i) => isRecord(mesh) && materialKeys(mesh.material, `meshes[${i}].material`));
  }
  return issues;
}

/** The least version that can say everything the scene uses. */
export function requiredVersion(scene: Scene): 1 | 2 | 3 {
  const materials = [...scene.spheres, ...scene.meshes, ...(scene.ground ? [scene.ground] : [])].map((o) => (o.material ? materialVersion(o.material) : 3));
  const v2Geometry = scene.meshes.length > 0 || (scene.environment !== null && 'map' in scene.environment);
  const lights = scene.lights.map(lightVersion);
  return Math.max(1, v2Geometry ? 2 : 1, ...materials, ...lights) as 1 | 2 | 3;
}

function isRecord(value: unknown): value is Record<string, unknown> {
  return typeof value === 'object' && value !== null && !Array.isArray(value);
}
