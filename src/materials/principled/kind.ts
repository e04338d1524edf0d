/**
 * Mitsuba 3's `principled` BSDF (scene format version 3), parameter for
 * parameter and choice for choice (src/bsdfs/principled.cpp and
 * principledhelpers.h of Mitsuba 3.9): Disney's diffuse with
 * retro-reflection (no fake subsurface: `flatness` 0), GGX with
 * alpha = max(0.001, roughness^2) and visible-normal sampling, the exact
 * Fresnel term of the boundary (relative index eta) blended with Schlick on the metal and the
 * specular tint, sheen, a GTR1 clear coat and rough transmission, with
 * Mitsuba's lobe-sampling probabilities (every sampling rate 1). With
 * `specTrans` 0 it is opaque (one-sided on spheres and the ground,
 * two-sided on meshes); any other `specTrans` makes it the boundary of a
 * solid, like glass. Textures, `normalMap` and `opacity` come with the
 * texture step: until then they are unknown keys. GLSL: principled.glsl.
 */
import * as z from 'zod';
import { MAX_IOR, MIN_IOR, type MaterialKind } from '../kind';
import { el, float, rgb } from '../../scene/mitsubaXml';
import { color, unit } from '../../scene/schemaParts';
import type { Emission, Vec3 } from '../../scene/types';

export interface PrincipledMaterial {
  type: 'principled';
  /** Linear base color, each channel in [0, 1] (Mitsuba's base_color). */
  baseColor: Vec3;
  metallic: number;
  /** GGX alpha = max(0.001, roughness^2). */
  roughness: number;
  /** Relative index of refraction inside / outside (Mitsuba's eta), in [1.01, 4]. */
  ior: number;
  specTint: number;
  specTrans: number;
  sheen: number;
  sheenTint: number;
  clearcoat: number;
  clearcoatGloss: number;
  emission?: Emission;
}

const DEFAULT_COLOR: Vec3 = [0.8, 0.8, 0.8];
/** The scalar keys after baseColor, in record order, with their Mitsuba names. */
const SCALARS = [
  ['metallic', 'metallic'],
  ['roughness', 'roughness'],
  ['ior', 'eta'],
  ['specTint', 'spec_tint'],
  ['specTrans', 'spec_trans'],
  ['sheen', 'sheen'],
  ['sheenTint', 'sheen_tint'],
  ['clearcoat', 'clearcoat'],
  ['clearcoatGloss', 'clearcoat_gloss'],
] as const;
type Scalar = (typeof SCALARS)[number][0];
const DEFAULTS: Record<Scalar, number> = {
  metallic: 0,
  roughness: 0.5,
  ior: 1.5,
  specTint: 0,
  specTrans: 0,
  sheen: 0,
  sheenTint: 0,
  clearcoat: 0,
  clearcoatGloss: 0,
};
const scalarsOf = (m: Record<string, unknown>) => Object.fromEntries(SCALARS.map(([key]) => [key, m[key] as number])) as Record<Scalar, number>;

const LABELS: Record<Scalar, string> = {
  metallic: 'metallic',
  roughness: 'roughness',
  ior: 'ior',
  specTint: 'specular tint',
  specTrans: 'transmission',
  sheen: 'sheen',
  sheenTint: 'sheen tint',
  clearcoat: 'clear coat',
  clearcoatGloss: 'clear coat gloss',
};

export const principled: MaterialKind<PrincipledMaterial> = {
  type: 'principled',
  version: 3,
  label: 'principled',
  shape: {
    baseColor: color(unit).default(() => [...DEFAULT_COLOR] as Vec3),
    ...Object.fromEntries(
      SCALARS.map(([key]) => [key, (key === 'ior' ? z.number().min(MIN_IOR).max(MAX_IOR) : unit()).default(DEFAULTS[key])]),
    ),
  },
  normalize: (p) => ({ type: 'principled', baseColor: p.baseColor as Vec3, ...scalarsOf(p) }),
  json: (m) => ({ baseColor: [...m.baseColor], ...scalarsOf(m as unknown as Record<string, unknown>) }),
  // 3 + 9 floats: texels 1 to 3 of the record exactly (metallic fills baseColor's texel).
  fields: [['baseColor', 'vec3'], ...SCALARS.map(([key]) => [key, 'float'] as [string, 'float'])],
  pack: (m) => ({ baseColor: m.baseColor, ...scalarsOf(m as unknown as Record<string, unknown>) }),
  glsl: '../materials/principled/principled.glsl',
  solid: (m) => m.specTrans > 0,
  solidWhen: '"principled" with specTrans above 0',
  mitsuba: (m) =>
    el('bsdf', { type: 'principled' }, [
      rgb('base_color', m.baseColor),
      ...SCALARS.map(([key, name]) => float(name, (m as unknown as Record<string, number>)[key])),
    ]),
  controls: [
    { control: 'color', key: 'baseColor', label: 'base color' },
    ...SCALARS.map(([key]) => ({
      control: 'number' as const,
      key,
      label: LABELS[key],
      min: key === 'ior' ? MIN_IOR : 0,
      max: key === 'ior' ? MAX_IOR : 1,
      step: 0.01,
    })),
  ],
  fromOther: (current) => ({
    type: 'principled',
    baseColor: [...(current.color ?? DEFAULT_COLOR)] as Vec3,
    ...DEFAULTS,
    roughness: current.roughness ?? DEFAULTS.roughness,
  }),
};
