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
 * solid, like glass. `baseColor`, `metallic`, `roughness`, `specTrans`,
 * `clearcoat` and `opacity` may be textures, `normalMap` is one (the
 * registry's texture slots: the record's constant is then the texture's
 * scale, surface.glsl multiplies in the lookup). GLSL: principled.glsl.
 */
import * as z from 'zod';
import { MAX_IOR, MIN_IOR, type MaterialKind } from '../kind';
import { el, float, rgb } from '../../scene/mitsubaXml';
import { color, unit } from '../../scene/schemaParts';
import { isTexture, normalMapSchema, scaleColor, texturable, textureJson, type Texture } from '../../scene/texture/texture';
import type { Emission, Vec3 } from '../../scene/types';

export interface PrincipledMaterial {
  type: 'principled';
  /** Linear base color, each channel in [0, 1] (Mitsuba's base_color), or a texture. */
  baseColor: Vec3 | Texture;
  metallic: number | Texture;
  /** GGX alpha = max(0.001, roughness^2). */
  roughness: number | Texture;
  /** Relative index of refraction inside / outside (Mitsuba's eta), in [1.01, 4]. */
  ior: number;
  specTint: number;
  specTrans: number | Texture;
  sheen: number;
  sheenTint: number;
  clearcoat: number | Texture;
  clearcoatGloss: number;
  /** 1: opaque; below 1 light passes straight through with probability 1 - opacity (Mitsuba's `mask`). */
  opacity: number | Texture;
  /** Perturbs the shading normal in the mesh's tangent frame (Mitsuba's `normalmap`). */
  normalMap?: Texture;
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
/** The scalar keys that may be textures (the others are numbers). */
const TEXTURED_SCALARS: readonly string[] = ['metallic', 'roughness', 'specTrans', 'clearcoat'];
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
const scalarsOf = (m: Record<string, unknown>) => Object.fromEntries(SCALARS.map(([key]) => [key, m[key]])) as Record<Scalar, number>;
/** A constant as is, a texture as its scale: the record holds the factor the lookup is multiplied by. */
const factorOf = (value: number | Texture) => (isTexture(value) ? (value.scale as number) : value);
const scalarJson = (key: string, value: unknown) => (isTexture(value) ? textureJson(value, 'scalar') : value);
const scalarSchema = (key: Scalar) => {
  const constant = (key === 'ior' ? z.number().min(MIN_IOR).max(MAX_IOR) : unit()).default(DEFAULTS[key]);
  return TEXTURED_SCALARS.includes(key) ? texturable(unit(), 'scalar').default(DEFAULTS[key]) : constant;
};

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
    baseColor: texturable(color(unit), 'color').default(() => [...DEFAULT_COLOR] as Vec3),
    ...Object.fromEntries(SCALARS.map(([key]) => [key, scalarSchema(key)])),
    opacity: texturable(unit(), 'scalar').default(1),
    normalMap: normalMapSchema().optional(),
  },
  normalize: (p) => ({
    type: 'principled',
    baseColor: p.baseColor as Vec3 | Texture,
    ...scalarsOf(p),
    opacity: p.opacity as number | Texture,
    ...(p.normalMap ? { normalMap: p.normalMap as Texture } : {}),
  }),
  json: (m) => ({
    baseColor: isTexture(m.baseColor) ? textureJson(m.baseColor, 'color') : [...m.baseColor],
    ...Object.fromEntries(SCALARS.map(([key]) => [key, scalarJson(key, m[key])])),
    opacity: scalarJson('opacity', m.opacity),
    ...(m.normalMap ? { normalMap: textureJson(m.normalMap, 'normal') } : {}),
  }),
  // 3 + 9 floats: texels 1 to 3 of the record exactly (metallic fills baseColor's texel).
  fields: [['baseColor', 'vec3'], ...SCALARS.map(([key]) => [key, 'float'] as [string, 'float'])],
  pack: (m) => ({
    baseColor: isTexture(m.baseColor) ? scaleColor(m.baseColor) : m.baseColor,
    ...Object.fromEntries(SCALARS.map(([key]) => [key, factorOf(m[key])])),
  }),
  textures: [
    { key: 'baseColor', input: 'color' },
    ...TEXTURED_SCALARS.map((key) => ({ key, input: 'scalar' as const })),
  ],
  opacity: (m) => m.opacity,
  texturedEmission: true,
  normalMap: (m) => m.normalMap,
  vertexColorKey: 'baseColor',
  glsl: '../materials/principled/principled.glsl',
  // A textured specTrans may transmit anywhere its image is not black.
  solid: (m) => isTexture(m.specTrans) || m.specTrans > 0,
  solidWhen: '"principled" with specTrans above 0',
  mitsuba: (m, textures) =>
    el('bsdf', { type: 'principled' }, [
      isTexture(m.baseColor) ? textures.bitmap('base_color', m.baseColor, 'color') : rgb('base_color', m.baseColor),
      ...SCALARS.map(([key, name]) => {
        const value = m[key] as number | Texture;
        return isTexture(value) ? textures.bitmap(name, value, 'scalar') : float(name, value);
      }),
    ]),
  controls: [
    { control: 'color', key: 'baseColor', label: 'base color', texturable: true },
    ...SCALARS.map(([key]) => ({
      control: 'number' as const,
      key,
      label: LABELS[key],
      min: key === 'ior' ? MIN_IOR : 0,
      max: key === 'ior' ? MAX_IOR : 1,
      step: 0.01,
      texturable: TEXTURED_SCALARS.includes(key),
    })),
    { control: 'number', key: 'opacity', label: 'opacity', min: 0, max: 1, step: 0.01, texturable: true },
    { control: 'texture', key: 'normalMap', label: 'normal map', input: 'normal' },
  ],
  fromOther: (current) => ({
    type: 'principled',
    baseColor: [...(current.color ?? DEFAULT_COLOR)] as Vec3,
    ...DEFAULTS,
    roughness: current.roughness ?? DEFAULTS.roughness,
    opacity: 1,
  }),
};
