/**
 * The directional light (version 3): parallel light travelling along
 * `direction` (from the light into the scene) with irradiance `color *
 * irradiance` on a surface facing it. Mitsuba: `directional`. A Dirac
 * delta with unbounded shadow rays (directional.glsl).
 */
import { el, rgb, triple } from '../../scene/mitsubaXml';
import { color, intensity, point, white } from '../../scene/schemaParts';
import type { Vec3 } from '../../scene/types';
import type { LightKind } from '../kind';
import { luminance, norm, normalize, scale, vec } from '../math';

export interface DirectionalLight {
  type: 'directional';
  /** The way the light travels (any length > 0). */
  direction: Vec3;
  color: Vec3;
  irradiance: number;
}

/** Shortest allowed `direction`. */
export const MIN_DIRECTION = 1e-6;

export const directional: LightKind<DirectionalLight> = {
  type: 'directional',
  version: 3,
  label: 'directional',
  shape: { direction: point(), color: color(intensity).default(white), irradiance: intensity().default(1) },
  check: (p) => (norm(p.direction as Vec3) < MIN_DIRECTION ? [['direction', 'must not be zero length']] : []),
  normalize: (p) => ({ type: 'directional', direction: vec(p.direction as Vec3), color: vec(p.color as Vec3), irradiance: p.irradiance as number }),
  json: (l) => ({ direction: vec(l.direction), color: vec(l.color), irradiance: l.irradiance }),
  create: () => ({ type: 'directional', direction: [-0.3, -1, -0.4], color: [1, 1, 1], irradiance: 1 }),
  fields: [['direction', 'vec3']],
  pack: (l) => ({ direction: normalize(l.direction) }),
  emitted: (l) => scale(l.color, l.irradiance),
  glsl: '../lights/directional/directional.glsl',
  delta: true,
  // pbrt-v4: the irradiance through the disk that bounds the scene.
  power: (l, bounds) => Math.PI * bounds.radius * bounds.radius * luminance(scale(l.color, l.irradiance)),
  // Its irradiance, the same everywhere.
  reach: (l) => ({ bound: null, strength: luminance(scale(l.color, l.irradiance)) }),
  extent: () => null,
  mitsuba: (l) => el('emitter', { type: 'directional' }, [el('vector', { name: 'direction', value: triple(normalize(l.direction)) }), rgb('irradiance', scale(l.color, l.irradiance))]),
  aim: 'direction',
  controls: [
    { control: 'color', key: 'color', label: 'color' },
    { control: 'number', key: 'irradiance', label: 'irradiance', min: 0, max: 50, step: 0.05 },
    { control: 'vector', key: 'direction', label: 'direction' },
  ],
};
