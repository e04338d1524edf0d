/**
 * The rectangle area light (version 3): `size` [w, h] in its local x-z
 * plane (w along x, h along z) at `position`, turned by `rotation`,
 * emitting radiance `color * intensity` from its lower face only (-y before
 * the rotation) and black from behind. Mitsuba: a `rectangle` shape with an
 * `area` emitter (src/lights/planar.ts). Seen by rays (the planar-light
 * table) and sampled by next-event estimation with MIS (rectangle.glsl).
 */
import * as z from 'zod';
import { color, intensity, MAX_COORDINATE, point, shapeError, white } from '../../scene/schemaParts';
import type { Vec3 } from '../../scene/types';
import type { LightKind } from '../kind';
import { luminance, planarReach, vec } from '../math';
import { planarAxes, planarMitsuba, radianceOf, rotationSchema } from '../planar';

export interface RectangleLight {
  type: 'rectangle';
  position: Vec3;
  rotation: Vec3;
  /** [w, h]: along local x and local z. */
  size: [number, number];
  color: Vec3;
  intensity: number;
}

const side = () => z.number().gt(0).max(MAX_COORDINATE);

export const rectangle: LightKind<RectangleLight> = {
  type: 'rectangle',
  version: 3,
  label: 'rectangle',
  shape: {
    position: point(),
    rotation: rotationSchema(),
    size: z.tuple([side(), side()], { error: shapeError('must be [w, h], each > 0') }),
    color: color(intensity).default(white),
    intensity: intensity().default(1),
  },
  normalize: (p) => {
    const size = p.size as [number, number];
    return { type: 'rectangle', position: vec(p.position as Vec3), rotation: vec(p.rotation as Vec3), size: [size[0], size[1]], color: vec(p.color as Vec3), intensity: p.intensity as number };
  },
  json: (l) => ({ position: vec(l.position), rotation: vec(l.rotation), size: [l.size[0], l.size[1]], color: vec(l.color), intensity: l.intensity }),
  create: (t) => ({ type: 'rectangle', position: [t[0], t[1] + 3, t[2]], rotation: [0, 0, 0], size: [1, 1], color: [1, 1, 1], intensity: 10 }),
  fields: [],
  pack: () => ({}),
  emitted: radianceOf,
  glsl: '../lights/rectangle/rectangle.glsl',
  delta: false,
  inside: 'max(abs(ab.x), abs(ab.y)) <= 1.0',
  area: (l) => ({ center: l.position, ...planarAxes(l.rotation, l.size[0] / 2, l.size[1] / 2), area: l.size[0] * l.size[1] }),
  // One face emits: pi * area * luminance(L).
  power: (l) => Math.PI * l.size[0] * l.size[1] * luminance(radianceOf(l)),
  reach: (l) => planarReach(rectangle.area!(l), radianceOf(l)),
  extent: (l) => ({ center: l.position, radius: Math.hypot(l.size[0], l.size[1]) / 2 }),
  mitsuba: (l) => planarMitsuba('rectangle', l.position, l.rotation, l.size[0] / 2, l.size[1] / 2, radianceOf(l)),
  aim: 'rotation',
  controls: [
    { control: 'color', key: 'color', label: 'color' },
    { control: 'number', key: 'intensity', label: 'intensity', min: 0, max: 500, step: 0.5 },
    { control: 'vector', key: 'rotation', label: 'rotation' },
    { control: 'vector', key: 'size', label: 'size' },
  ],
};
