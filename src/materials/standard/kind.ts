/**
 * The standard material (scene format version 1): a blend of a
 * Fresnel-less GGX microfacet mirror and Lambert, `(1 - r) * GGX (alpha = r^2) + r *
 * Lambert`, both tinted by `color`. Mitsuba: `blendbsdf` with weight = r,
 * first child the specular lobe (`conductor` or `roughconductor` with
 * material="none", specular_reflectance = color), second `diffuse`; pure
 * r = 0 and r = 1 skip the blend. GLSL: standard.glsl.
 */
import { DELTA_ALPHA, type MaterialKind } from '../kind';
import { el, float, ggxLobe, rgb, str } from '../../scene/mitsubaXml';
import { color, unit } from '../../scene/schemaParts';
import type { Emission, Vec3 } from '../../scene/types';

export interface StandardMaterial {
  type: 'standard';
  /** Linear albedo, each channel in [0, 1]. */
  color: Vec3;
  /** 0 = ideal mirror, 1 = Lambertian; the BSDF blends GGX (alpha = r^2) and Lambert. */
  roughness: number;
  emission?: Emission;
}

const DEFAULT_COLOR: Vec3 = [0.8, 0.8, 0.8];

export const standard: MaterialKind<StandardMaterial> = {
  type: 'standard',
  version: 1,
  label: 'standard',
  shape: { color: color(unit).default(() => [...DEFAULT_COLOR] as Vec3), roughness: unit().default(1) },
  normalize: (p) => ({ type: 'standard', color: p.color as Vec3, roughness: p.roughness as number }),
  json: (m) => ({ color: [...m.color], roughness: m.roughness }),
  fields: [['color', 'vec3'], ['roughness', 'float']],
  pack: (m) => ({ color: m.color, roughness: m.roughness }),
  glsl: '../materials/standard/standard.glsl',
  solid: () => false,
  mitsuba: (m) => {
    const r = m.roughness;
    const diffuse = el('bsdf', { type: 'diffuse' }, [rgb('reflectance', m.color)]);
    const mirror = [str('material', 'none'), rgb('specular_reflectance', m.color)];
    const specular = r === 0 ? el('bsdf', { type: 'conductor' }, mirror) : el('bsdf', { type: 'roughconductor' }, [mirror[0], ...ggxLobe(r), mirror[1]]);
    // blendbsdf: weight 0 selects the first child, 1 the second.
    return r === 0 ? specular : r === 1 ? diffuse : el('bsdf', { type: 'blendbsdf' }, [float('weight', r), specular, diffuse]);
  },
  controls: [
    { control: 'color', key: 'color', label: 'color' },
    { control: 'number', key: 'roughness', label: 'roughness', min: 0, max: 1, step: 0.01 },
  ],
  fromOther: (current) => ({ type: 'standard', color: [...(current.color ?? DEFAULT_COLOR)] as Vec3, roughness: current.roughness ?? 1 }),
  idealMirror: (m) => (m.roughness * m.roughness < DELTA_ALPHA ? { weight: 1 - m.roughness, albedo: Math.max(...m.color) } : null),
};
