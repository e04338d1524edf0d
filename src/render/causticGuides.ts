/**
 * Which (mirror sphere, emitting sphere) pairs the caustic guides aim at
 * (see src/shaders/lights/caustic_guide.glsl), and their tuning constants.
 */
import { kindOf } from '../materials/registry';
import type { Material, Vec3 } from '../scene/types';
import { MAX_GUIDES } from './layout/scene';

export { DELTA_ALPHA } from '../materials/kind';

/**
 * The probability of drawing a rough vertex's next direction towards a
 * light's image in a mirror (scaled by the material's guide weight); how much
 * wider than the estimated image the cone is.
 */
export const GUIDE_PROBABILITY = 0.1;
export const GUIDE_MARGIN = 2.0;
/** A sphere is a guiding mirror when its specular lobe is a delta and carries at least this weight. */
export const GUIDE_MIN_SPECULAR = 0.5;

export interface GuideSphere {
  center: Vec3;
  radius: number;
  material: Material | 'emitterOnly';
  radiance: Vec3;
}

/**
 * Spheres whose material has an ideal-mirror lobe with most of the weight
 * (the kind's `idealMirror`), paired with every emitting sphere, ranked by the emitter's power
 * times the mirror's size and albedo. At most MAX_GUIDES pairs of indices.
 */
export function selectCausticGuides(spheres: readonly GuideSphere[]): [number, number][] {
  const pairs: { pair: [number, number]; score: number }[] = [];
  spheres.forEach((mirror, m) => {
    const material = mirror.material;
    const ideal = material === 'emitterOnly' ? null : (kindOf(material).idealMirror?.(material) ?? null);
    if (!ideal || ideal.weight < GUIDE_MIN_SPECULAR) return;
    spheres.forEach((light, l) => {
      const power = Math.max(...light.radiance) * light.radius ** 2;
      if (l !== m && power > 0) pairs.push({ pair: [m, l], score: power * mirror.radius ** 2 * ideal.albedo });
    });
  });
  return pairs.sort((a, b) => b.score - a.score).slice(0, MAX_GUIDES).map((p) => p.pair);
}
