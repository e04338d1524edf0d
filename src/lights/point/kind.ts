/**
 * The point light (version 3): radiant intensity `color * intensity` (per
 * steradian) in every direction from `position`. Mitsuba: `point`. A Dirac
 * delta: reached only by next-event estimation (point.glsl).
 */
import { el, point as pointXml, rgb } from '../../scene/mitsubaXml';
import { color, intensity, point, white } from '../../scene/schemaParts';
import type { Vec3 } from '../../scene/types';
import type { LightKind } from '../kind';
import { luminance, scale, vec } from '../math';

export interface PointLight {
  type: 'point';
  position: Vec3;
  color: Vec3;
  intensity: number;
}

export const pointLight: LightKind<PointLight> = {
  type: 'point',
  version: 3,
  label: 'point',
  shape: { position: point(), color: color(intensity).default(white), intensity: intensity().default(1) },
  normalize: (p) => ({ type: 'point', position: vec(p.position as Vec3), color: vec(p.color as Vec3), intensity: p.intensity as number }),
  json: (l) => ({ position: vec(l.position), color: vec(l.color), intensity: l.intensity }),
  create: (t) => ({ type: 'point', position: [t[0] + 1, t[1] + 2, t[2] + 1], color: [1, 1, 1], intensity: 10 }),
  fields: [['position', 'vec3']],
  pack: (l) => ({ position: l.position }),
  emitted: (l) => scale(l.color, l.intensity),
  glsl: '../lights/point/point.glsl',
  delta: true,
  // 4 pi steradians of intensity I.
  power: (l) => 4 * Math.PI * luminance(scale(l.color, l.intensity)),
  // Intensity I: I / d^2 at distance d, every way.
  reach: (l) => ({ bound: { center: l.position, radius: 0 }, strength: luminance(scale(l.color, l.intensity)) }),
  extent: (l) => ({ center: l.position, radius: 0 }),
  mitsuba: (l) => el('emitter', { type: 'point' }, [pointXml('position', l.position), rgb('intensity', scale(l.color, l.intensity))]),
  controls: [
    { control: 'color', key: 'color', label: 'color' },
    { control: 'number', key: 'intensity', label: 'intensity', min: 0, max: 500, step: 0.5 },
  ],
};
