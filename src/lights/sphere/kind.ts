/**
 * The sphere light (scene format version 1, the default `type`): a sphere
 * of radius `radius` emitting radiance `color * intensity` in all outward
 * directions, reflecting nothing. Mitsuba: a `sphere` shape with an `area`
 * emitter and a black `diffuse` BSDF. Sampled uniformly in the cone it
 * subtends (sphere.glsl), as emissive spheres are.
 */
import { el, float, point, rgb } from '../../scene/mitsubaXml';
import { color, intensity, length, point as pointSchema, white } from '../../scene/schemaParts';
import type { Vec3 } from '../../scene/types';
import type { LightKind } from '../kind';
import { luminance, scale, sphereReach, vec } from '../math';

export interface SphereLight {
  type: 'sphere';
  position: Vec3;
  radius: number;
  color: Vec3;
  intensity: number;
}

/** Power of a sphere emitting radiance L from its whole surface: pi * 4 pi r^2 * luminance(L). */
export const spherePower = (radius: number, radiance: Vec3) => 4 * Math.PI * Math.PI * radius * radius * luminance(radiance);

export const sphere: LightKind<SphereLight> = {
  type: 'sphere',
  version: 1,
  label: 'sphere',
  shape: { position: pointSchema(), radius: length(), color: color(intensity).default(white), intensity: intensity().default(1) },
  normalize: (p) => ({ type: 'sphere', position: vec(p.position as Vec3), radius: p.radius as number, color: vec(p.color as Vec3), intensity: p.intensity as number }),
  json: (l) => ({ position: vec(l.position), radius: l.radius, color: vec(l.color), intensity: l.intensity }),
  create: (t) => ({ type: 'sphere', position: [t[0] + 1, t[1] + 3, t[2] + 1], radius: 0.3, color: [1, 1, 1], intensity: 40 }),
  fields: [['center', 'vec3'], ['radius', 'float']],
  pack: (l) => ({ center: l.position, radius: l.radius }),
  emitted: (l) => scale(l.color, l.intensity),
  glsl: '../lights/sphere/sphere.glsl',
  delta: false,
  sphere: (l) => ({ center: l.position, radius: l.radius }),
  power: (l) => spherePower(l.radius, scale(l.color, l.intensity)),
  reach: (l) => sphereReach(l.position, l.radius, scale(l.color, l.intensity)),
  extent: (l) => ({ center: l.position, radius: l.radius }),
  mitsuba: (l) => {
    const radiance = scale(l.color, l.intensity);
    const black = radiance.every((c) => c === 0);
    return el('shape', { type: 'sphere' }, [
      point('center', l.position),
      float('radius', l.radius),
      el('bsdf', { type: 'diffuse' }, [rgb('reflectance', [0, 0, 0])]),
      ...(black ? [] : [el('emitter', { type: 'area' }, [rgb('radiance', radiance)])]),
    ]);
  },
  controls: [
    { control: 'color', key: 'color', label: 'color' },
    { control: 'number', key: 'intensity', label: 'intensity', min: 0, max: 500, step: 0.5 },
    { control: 'number', key: 'radius', label: 'radius', min: 0.01, max: 5, step: 0.01 },
  ],
};
