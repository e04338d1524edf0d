/**
 * What the two planar area lights (rectangle, disk) share: their rotation
 * key, their frame (half-axes u along local x and v along local z after the
 * rotation, emitting towards cross(u, v) = the rotated -y) and their
 * Mitsuba export (the format's `to_world = translate(position) * Rz * Ry *
 * Rx * rotate_x(90) * scale(sx, sy, 1)`: Mitsuba's shape lies in its local
 * x-y plane and emits along +z, which rotate_x(90) turns to -y).
 */
import * as z from 'zod';
import { el, num, rgb, triple } from '../scene/mitsubaXml';
import { shapeError } from '../scene/schemaParts';
import type { Vec3 } from '../scene/types';
import { rotate, scale } from './math';

const angle = () => z.number().min(-1e6).max(1e6);
/** `rotation`: degrees about x, then y, then z (world axes), as for meshes. */
export const rotationSchema = () =>
  z.tuple([angle(), angle(), angle()], { error: shapeError('must be [x, y, z] in degrees') }).default((): Vec3 => [0, 0, 0]);

/** The half-axes of a planar light of half-sizes (sx, sz) turned by `rotation`. */
export function planarAxes(rotation: Vec3, sx: number, sz: number): { u: Vec3; v: Vec3 } {
  return { u: rotate(rotation, [sx, 0, 0]), v: rotate(rotation, [0, 0, sz]) };
}

/** Mitsuba's `shape` (rectangle or disk) with an `area` emitter of `radiance` and a black diffuse BSDF (lights reflect nothing). */
export function planarMitsuba(type: 'rectangle' | 'disk', position: Vec3, rotation: Vec3, sx: number, sy: number, radiance: Vec3) {
  const black = radiance.every((c) => c === 0);
  return el('shape', { type }, [
    el('transform', { name: 'to_world' }, [
      el('scale', { value: triple([sx, sy, 1]) }),
      el('rotate', { x: '1', angle: '90' }),
      el('rotate', { x: '1', angle: num(rotation[0]) }),
      el('rotate', { y: '1', angle: num(rotation[1]) }),
      el('rotate', { z: '1', angle: num(rotation[2]) }),
      el('translate', { value: triple(position) }),
    ]),
    el('bsdf', { type: 'diffuse' }, [rgb('reflectance', [0, 0, 0])]),
    ...(black ? [] : [el('emitter', { type: 'area' }, [rgb('radiance', radiance)])]),
  ]);
}

export const radianceOf = (l: { color: Vec3; intensity: number }) => scale(l.color, l.intensity);
