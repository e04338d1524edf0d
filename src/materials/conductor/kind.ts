/**
 * A metal (scene format version 3): exactly Mitsuba 3's `conductor`
 * (roughness 0) and `roughconductor` (GGX, alpha = r^2, visible-normal
 * sampling) with its exact complex Fresnel term (`fresnel_conductor`),
 * `specular_reflectance` = color. Either a named metal of Mitsuba's table
 * (metals.ts: the RGB eta and k of its RGB mode) or eta and k given; "none"
 * is the ideal mirror (reflectance 1). One-sided on spheres and the ground,
 * two-sided on meshes (the format's sidedness rule). GLSL: conductor.glsl.
 */
import * as z from 'zod';
import type { MaterialKind } from '../kind';
import { el, ggxLobe, rgb, str } from '../../scene/mitsubaXml';
import { color, unit, white } from '../../scene/schemaParts';
import type { Emission, Vec3 } from '../../scene/types';
import { METALS, METAL_NAMES } from './metals';

export interface ConductorMaterial {
  type: 'conductor';
  /** The metal of Mitsuba's table that gave eta and k; absent when they were given. */
  metal?: string;
  /** Real and imaginary parts of the metal's relative index of refraction, per channel. */
  eta: Vec3;
  k: Vec3;
  /** 0 = smooth; above, GGX with alpha = r^2. */
  roughness: number;
  /** Tint multiplying the Fresnel term (Mitsuba's specular_reflectance). */
  color: Vec3;
  emission?: Emission;
}

/** Largest eta or k accepted (the measured metals stay below 12). */
const MAX_INDEX = 100;
const DEFAULT_METAL = 'Al';
const index = () => z.tuple([0, 1, 2].map(() => z.number().gt(0).max(MAX_INDEX)) as [z.ZodNumber, z.ZodNumber, z.ZodNumber], { error: (i) => (i.input === undefined ? undefined : 'must be [r, g, b]') });
const CUSTOM = 'custom';

const table = (metal: string) => METALS[metal];
const vec = (v: readonly number[]): Vec3 => [v[0], v[1], v[2]];

export const conductor: MaterialKind<ConductorMaterial> = {
  type: 'conductor',
  version: 3,
  label: 'conductor',
  shape: {
    metal: z.string().refine((name) => name in METALS, { message: `must be one of ${METAL_NAMES.map((n) => `"${n}"`).join(', ')}` }).optional(),
    eta: index().optional(),
    k: index().optional(),
    roughness: unit().default(0),
    color: color(unit).default(white),
  },
  check: (p) => {
    if (p.metal !== undefined && (p.eta !== undefined || p.k !== undefined)) return [[p.eta !== undefined ? 'eta' : 'k', 'is not allowed with "metal" (give a metal or eta and k)']];
    if ((p.eta === undefined) !== (p.k === undefined)) return [[p.eta === undefined ? 'eta' : 'k', 'required with "' + (p.eta === undefined ? 'k' : 'eta') + '" (give both, or a metal)']];
    return [];
  },
  normalize: (p) => {
    const given = p.eta !== undefined;
    const metal = given ? undefined : ((p.metal as string | undefined) ?? DEFAULT_METAL);
    const ior = metal === undefined ? { eta: p.eta as Vec3, k: p.k as Vec3 } : table(metal);
    return { type: 'conductor', ...(metal === undefined ? {} : { metal }), eta: vec(ior.eta), k: vec(ior.k), roughness: p.roughness as number, color: p.color as Vec3 };
  },
  json: (m) => ({ ...(m.metal === undefined ? { eta: [...m.eta], k: [...m.k] } : { metal: m.metal }), roughness: m.roughness, color: [...m.color] }),
  fields: [['color', 'vec3'], ['roughness', 'float'], ['eta', 'vec3'], ['k', 'vec3']],
  pack: (m) => ({ color: m.color, roughness: m.roughness, eta: m.eta, k: m.k }),
  glsl: '../materials/conductor/conductor.glsl',
  solid: () => false,
  mitsuba: (m) => {
    const ior = m.metal === undefined ? [rgb('eta', m.eta), rgb('k', m.k)] : [str('material', m.metal)];
    const common = [...ior, rgb('specular_reflectance', m.color)];
    return m.roughness === 0 ? el('bsdf', { type: 'conductor' }, common) : el('bsdf', { type: 'roughconductor' }, [...ggxLobe(m.roughness), ...common]);
  },
  controls: [
    {
      control: 'choice',
      key: 'metal',
      label: 'metal',
      options: [...METAL_NAMES, CUSTOM],
      get: (m: ConductorMaterial) => m.metal ?? CUSTOM,
      // "custom" keeps the current eta and k, given explicitly from then on.
      set: (m: ConductorMaterial, option: string) => {
        if (option === CUSTOM || !(option in METALS)) delete m.metal;
        else Object.assign(m, { metal: option, eta: vec(table(option).eta), k: vec(table(option).k) });
      },
    },
    { control: 'color', key: 'color', label: 'tint' },
    { control: 'number', key: 'roughness', label: 'roughness', min: 0, max: 1, step: 0.01 },
  ],
  fromOther: (current) => ({ type: 'conductor', metal: DEFAULT_METAL, eta: vec(table(DEFAULT_METAL).eta), k: vec(table(DEFAULT_METAL).k), roughness: current.roughness === 1 ? 0.2 : (current.roughness ?? 0), color: [1, 1, 1] }),
};
