/**
 * Scene -> the Float32Array behind the std140 `SceneBlock` uniform block.
 * Pure: no GL, so it is unit-tested directly.
 */
import type { Material, Scene } from '../scene/types';
import { BLOCK, GROUND_FIELDS, LIGHT_FIELDS, LIGHT_VEC4S, SPHERE_FIELDS, SPHERE_VEC4S } from './layout';

export function packScene(scene: Scene): Float32Array {
  const data = new Float32Array(BLOCK.size * 4);
  const put = (vec4: number, values: readonly number[]) => data.set(values, vec4 * 4);
  const material = (m: Material) => [...m.color, m.roughness];

  scene.spheres.forEach((sphere, i) => {
    const base = BLOCK.spheres + i * SPHERE_VEC4S;
    put(base + SPHERE_FIELDS.GEOMETRY, [...sphere.center, sphere.radius]);
    put(base + SPHERE_FIELDS.MATERIAL, material(sphere.material));
  });
  scene.lights.forEach((light, i) => {
    const base = BLOCK.lights + i * LIGHT_VEC4S;
    put(base + LIGHT_FIELDS.GEOMETRY, [...light.position, light.radius]);
    put(base + LIGHT_FIELDS.RADIANCE, light.color.map((c) => c * light.intensity));
  });
  if (scene.ground) {
    put(BLOCK.ground + GROUND_FIELDS.GEOMETRY, [scene.ground.height, 0, 0, 0]);
    put(BLOCK.ground + GROUND_FIELDS.MATERIAL, material(scene.ground.material));
  }
  const environment = scene.environment;
  if (environment) put(BLOCK.environment, environment.color.map((c) => c * environment.intensity));
  put(BLOCK.counts, [scene.spheres.length, scene.lights.length, scene.ground ? 1 : 0, 0]);
  return data;
}
