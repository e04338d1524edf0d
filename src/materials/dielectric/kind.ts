/**
 * Glass: the boundary of a transparent solid, exactly Mitsuba 3's
 * `dielectric` (roughness 0) and `roughdielectric` (GGX, alpha = r^2,
 * visible normals) with int_ior = ior, ext_ior = 1 and
 * specular_transmittance = color (scene format version 2). GLSL:
 * dielectric.glsl.
 */
import { MAX_IOR, MIN_IOR, type MaterialKind } from '../kind';
import { el, float, ggxLobe, rgb } from '../../scene/mitsubaXml';
import { color, unit, white } from '../../scene/schemaParts';
import type { Emission, Vec3 } from '../../scene/types';
import * as z from 'zod';


export interface DielectricMaterial {
  type: 'dielectric';
  /** Tint of refracted light, per crossing; reflection is not tinted. */
  color: Vec3;
  /** 0 = smooth; above, GGX with alpha = r^2. */
  roughness: number;
  /** Index of refraction inside, in [1.01, 4]; outside is 1. */
  ior: number;
  emission?: Emission;
}

/** Clear glass, what "make it glass" means: untinted, smooth, ior of window glass. */
const NEW_GLASS = { color: [1, 1, 1] as Vec3, roughness: 0, ior: 1.5 };

export const dielectric: MaterialKind<DielectricMaterial> = {
  type: 'dielectric',
  version: 2,
  label: 'dielectric',
  shape: { color: color(unit).default(white), roughness: unit().default(0), ior: z.number().min(MIN_IOR).max(MAX_IOR).default(1.5) },
  normalize: (p) => ({ type: 'dielectric', color: p.color as Vec3, roughness: p.roughness as number, ior: p.ior as number }),
  json: (m) => ({ color: [...m.color], roughness: m.roughness, ior: m.ior }),
  fields: [['color', 'vec3'], ['roughness', 'float'], ['ior', 'float']],
  pack: (m) => ({ color: m.color, roughness: m.roughness, ior: m.ior }),
  glsl: '../materials/dielectric/dielectric.glsl',
  solid: () => true,
  solidWhen: '"dielectric"',
  mitsuba: (m) => {
    const common = [float('int_ior', m.ior), float('ext_ior', 1), rgb('specular_transmittance', m.color)];
    return m.roughness === 0 ? el('bsdf', { type: 'dielectric' }, common) : el('bsdf', { type: 'roughdielectric' }, [...ggxLobe(m.roughness), ...common]);
  },
  controls: [
    { control: 'color', key: 'color', label: 'tint' },
    { control: 'number', key: 'roughness', label: 'roughness', min: 0, max: 1, step: 0.01 },
    { control: 'number', key: 'ior', label: 'ior', min: MIN_IOR, max: MAX_IOR, step: 0.01 },
  ],
  // An opaque surface's albedo used as a per-crossing tint would make dark, saturated glass: clear glass instead.
  fromOther: () => ({ type: 'dielectric', color: [...NEW_GLASS.color], roughness: NEW_GLASS.roughness, ior: NEW_GLASS.ior }),
};
