/**
 * The spot light (version 3): radiant intensity `color * intensity` from
 * `position` towards `target`, full inside `beamWidth` degrees of the axis
 * and falling linearly in angle to 0 at `cutoffAngle` (Mitsuba's `spot`,
 * src/emitters/spot.cpp falloff_curve: 1 where cos >= cos(beamWidth), else
 * (cutoff - acos(cos)) / (cutoff - beamWidth); 0 where cos <= cos(cutoff)).
 * A Dirac delta: reached only by next-event estimation (spot.glsl).
 */
import * as z from 'zod';
import { el, float, rgb, triple } from '../../scene/mitsubaXml';
import { color, intensity, point, white } from '../../scene/schemaParts';
import type { Vec3 } from '../../scene/types';
import type { LightKind } from '../kind';
import { luminance, norm, normalize, scale, sub, toRadians, vec } from '../math';

export interface SpotLight {
  type: 'spot';
  position: Vec3;
  target: Vec3;
  color: Vec3;
  intensity: number;
  /** Degrees from the axis where the light ends, in (0, 90]. */
  cutoffAngle: number;
  /** Degrees from the axis of full intensity, in [0, cutoffAngle]. */
  beamWidth: number;
}

/** Closest `target` may come to `position` (the axis must have a direction). */
export const MIN_SPOT_AXIS = 1e-6;
const CUTOFF = 'must be in (0, 90]';

/** The record's cone: cosines of both angles, the cutoff in radians and 1 / the transition's width (0 when it has none). */
export function spotCone(l: SpotLight) {
  const cutoff = toRadians(l.cutoffAngle);
  const beam = toRadians(l.beamWidth);
  return { cosCutoff: Math.cos(cutoff), cosBeam: Math.cos(beam), cutoff, invTransition: cutoff > beam ? 1 / (cutoff - beam) : 0 };
}

/** A `lookat` up vector not parallel to the axis (the spot is round: any will do). */
const upFor = (axis: Vec3): Vec3 => (Math.abs(axis[1]) < 0.9 ? [0, 1, 0] : [1, 0, 0]);

export const spot: LightKind<SpotLight> = {
  type: 'spot',
  version: 3,
  label: 'spot',
  shape: {
    position: point(),
    target: point(),
    color: color(intensity).default(white),
    intensity: intensity().default(1),
    cutoffAngle: z.number().gt(0, CUTOFF).max(90, CUTOFF).default(20),
    beamWidth: z.number().min(0, 'must be >= 0').optional(),
  },
  check: (p) => {
    const problems: [string, string][] = [];
    if (norm(sub(p.target as Vec3, p.position as Vec3)) < MIN_SPOT_AXIS) problems.push(['target', 'must differ from position']);
    if (p.beamWidth !== undefined && (p.beamWidth as number) > (p.cutoffAngle as number)) problems.push(['beamWidth', `must be <= cutoffAngle (${p.cutoffAngle})`]);
    return problems;
  },
  normalize: (p) => ({
    type: 'spot',
    position: vec(p.position as Vec3),
    target: vec(p.target as Vec3),
    color: vec(p.color as Vec3),
    intensity: p.intensity as number,
    cutoffAngle: p.cutoffAngle as number,
    beamWidth: (p.beamWidth as number | undefined) ?? 0.75 * (p.cutoffAngle as number),
  }),
  json: (l) => ({ position: vec(l.position), target: vec(l.target), color: vec(l.color), intensity: l.intensity, cutoffAngle: l.cutoffAngle, beamWidth: l.beamWidth }),
  create: (t) => ({ type: 'spot', position: [t[0] + 1, t[1] + 3, t[2] + 1], target: vec(t), color: [1, 1, 1], intensity: 40, cutoffAngle: 20, beamWidth: 15 }),
  fields: [['position', 'vec3'], ['cosCutoff', 'float'], ['axis', 'vec3'], ['cosBeam', 'float'], ['cutoff', 'float'], ['invTransition', 'float']],
  pack: (l) => {
    const { cosCutoff, cosBeam, cutoff, invTransition } = spotCone(l);
    return { position: l.position, axis: normalize(sub(l.target, l.position)), cosCutoff, cosBeam, cutoff, invTransition };
  },
  emitted: (l) => scale(l.color, l.intensity),
  glsl: '../lights/spot/spot.glsl',
  delta: true,
  // pbrt-v4's estimate: the cone's solid angle up to the middle of the transition.
  power: (l) => {
    const { cosCutoff, cosBeam } = spotCone(l);
    return 2 * Math.PI * (1 - 0.5 * (cosCutoff + cosBeam)) * luminance(scale(l.color, l.intensity));
  },
  // I / d^2 at most, and nothing outside the cutoff cone.
  reach: (l) => ({
    bound: { center: l.position, radius: 0 },
    strength: luminance(scale(l.color, l.intensity)),
    cone: { axis: normalize(sub(l.target, l.position)), cosCutoff: spotCone(l).cosCutoff },
  }),
  extent: (l) => ({ center: l.position, radius: 0 }),
  mitsuba: (l) => {
    const axis = normalize(sub(l.target, l.position));
    return el('emitter', { type: 'spot' }, [
      el('transform', { name: 'to_world' }, [el('lookat', { origin: triple(l.position), target: triple(l.target), up: triple(upFor(axis)) })]),
      rgb('intensity', scale(l.color, l.intensity)),
      float('cutoff_angle', l.cutoffAngle),
      float('beam_width', l.beamWidth),
    ]);
  },
  aim: 'target',
  controls: [
    { control: 'color', key: 'color', label: 'color' },
    { control: 'number', key: 'intensity', label: 'intensity', min: 0, max: 500, step: 0.5 },
    { control: 'vector', key: 'target', label: 'target' },
    { control: 'number', key: 'cutoffAngle', label: 'cutoff angle', min: 0.1, max: 90, step: 0.1 },
    { control: 'number', key: 'beamWidth', label: 'beam width', min: 0, max: 90, step: 0.1 },
  ],
};
