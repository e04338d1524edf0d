/**
 * The disk area light (version 3): radius `radius` in its local x-z plane
 * at `position`, turned by `rotation`, emitting radiance `color *
 * intensity` from its lower face only (-y before the rotation), black from
 * behind. Mitsuba: a `disk` shape with an `area` emitter (src/lights/planar.ts).
 * Seen by rays and sampled uniformly by area (disk.glsl), with MIS.
 */
import { color, intensity, length, point, white } from '../../scene/schemaParts';
import type { Vec3 } from '../../scene/types';
import type { LightKind } from '../kind';
import { luminance, planarReach, vec } from '../math';
import { planarAxes, planarMitsuba, radianceOf, rotationSchema } from '../planar';

export interface DiskLight {
  type: 'disk';
  position: Vec3;
  rotation: Vec3;
  radius: number;
  color: Vec3;
  intensity: number;
}

export const disk: LightKind<DiskLight> = {
  type: 'disk',
  version: 3,
  label: 'disk',
  shape: { position: point(), rotation: rotationSchema(), radius: length(), color: color(intensity).default(white), intensity: intensity().default(1) },
  normalize: (p) => ({ type: 'disk', position: vec(p.position as Vec3), rotation: vec(p.rotation as Vec3), radius: p.radius as number, color: vec(p.color as Vec3), intensity: p.intensity as number }),
  json: (l) => ({ position: vec(l.position), rotation: vec(l.rotation), radius: l.radius, color: vec(l.color), intensity: l.intensity }),
  create: (t) => ({ type: 'disk', position: [t[0], t[1] + 3, t[2]], rotation: [0, 0, 0], radius: 0.5, color: [1, 1, 1], intensity: 10 }),
  fields: [],
  pack: () => ({}),
  emitted: radianceOf,
  glsl: '../lights/disk/disk.glsl',
  delta: false,
  inside: 'dot(ab, ab) <= 1.0',
  area: (l) => ({ center: l.position, ...planarAxes(l.rotation, l.radius, l.radius), area: Math.PI * l.radius * l.radius }),
  power: (l) => Math.PI * Math.PI * l.radius * l.radius * luminance(radianceOf(l)),
  reach: (l) => planarReach(disk.area!(l), radianceOf(l)),
  extent: (l) => ({ center: l.position, radius: l.radius }),
  mitsuba: (l) => planarMitsuba('disk', l.position, l.rotation, l.radius, l.radius, radianceOf(l)),
  aim: 'rotation',
  controls: [
    { control: 'color', key: 'color', label: 'color' },
    { control: 'number', key: 'intensity', label: 'intensity', min: 0, max: 500, step: 0.5 },
    { control: 'vector', key: 'rotation', label: 'rotation' },
    { control: 'number', key: 'radius', label: 'radius', min: 0.01, max: 5, step: 0.01 },
  ],
};
