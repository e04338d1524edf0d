/**
 * Scene -> the Float32Array behind the std140 `SceneBlock` uniform block.
 * Pure: no GL, so it is unit-tested directly.
 */
import type { Material, Scene } from '../scene/types';
import {
  BLOCK, GROUND_FIELDS, GUIDE_FIELDS, GUIDE_MIN_SPECULAR, GUIDE_VEC4S, LIGHT_FIELDS, LIGHT_VEC4S, MAX_GUIDES, SMOOTH_ALPHA, SPHERE_FIELDS, SPHERE_VEC4S,
} from './layout';

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
  const guides = causticGuides(scene);
  // The guides' geometry itself, not indices: the shader reads it with
  // constant indices, which SwiftShader does without a texture fetch.
  guides.forEach(([sphere, light], i) => {
    const { center, radius } = scene.spheres[sphere];
    const { position, radius: lightRadius } = scene.lights[light];
    put(BLOCK.guides + i * GUIDE_VEC4S + GUIDE_FIELDS.MIRROR, [...center, radius]);
    put(BLOCK.guides + i * GUIDE_VEC4S + GUIDE_FIELDS.LIGHT, [...position, lightRadius]);
  });
  put(BLOCK.counts, [scene.spheres.length, scene.lights.length, scene.ground ? 1 : 0, guides.length]);
  return data;
}

/**
 * The (mirror sphere, light) pairs worth guiding towards, brightest first:
 * spheres whose specular lobe is an ideal mirror (alpha below SMOOTH_ALPHA)
 * with most of the weight, paired with every light, ranked by the light's
 * power times the mirror's size. At most MAX_GUIDES.
 */
export function causticGuides(scene: Scene): [number, number][] {
  const pairs: { pair: [number, number]; score: number }[] = [];
  scene.spheres.forEach((sphere, s) => {
    const r = sphere.material.roughness;
    if (r * r >= SMOOTH_ALPHA || 1 - r < GUIDE_MIN_SPECULAR) return;
    scene.lights.forEach((light, l) => {
      const power = light.intensity * Math.max(...light.color) * light.radius ** 2;
      if (power > 0) pairs.push({ pair: [s, l], score: power * sphere.radius ** 2 * Math.max(...sphere.material.color) });
    });
  });
  return pairs.sort((a, b) => b.score - a.score).slice(0, MAX_GUIDES).map((p) => p.pair);
}
