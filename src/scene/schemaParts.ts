/**
 * The value schemas that the scene schema (schema.ts) and the material
 * plugins (src/materials/) share: numbers with their ranges, colors,
 * emission. Imports nothing of the schema itself, so plugins can use it
 * while the schema imports the plugins' registry.
 */
import * as z from 'zod';
import { hexToLinear, isHexColor } from './color';
import type { Vec3 } from './types';

/** Largest magnitude of a coordinate, a radius, a ground height or an aperture. */
export const MAX_COORDINATE = 1e6;
/**
 * Largest light or environment intensity and emitted color channel: their
 * product stays far inside the range of the shader's 32-bit floats.
 */
export const MAX_INTENSITY = 1e12;

/** The error of a schema's own type or shape check; a missing value stays "required". */
export const shapeError = (message: string) => (issue: { input?: unknown }) =>
  issue.input === undefined ? undefined : message;

export const coordinate = () => z.number().min(-MAX_COORDINATE).max(MAX_COORDINATE);
export const length = () => z.number().gt(0).max(MAX_COORDINATE);
export const unit = () => z.number().min(0).max(1);
export const intensity = () => z.number().min(0).max(MAX_INTENSITY);
export const integer = (min: number, max: number) => z.number().min(min).max(max).int();

export const point = () =>
  z.tuple([coordinate(), coordinate(), coordinate()], { error: shapeError('must be [x, y, z]') });

/** [r, g, b] in linear RGB, or "#rrggbb" in sRGB (converted to linear before the channel checks). */
export const color = (channel: () => z.ZodNumber) =>
  z.preprocess(
    (value) => (isHexColor(value) ? hexToLinear(value) : value),
    z.tuple([channel(), channel(), channel()], { error: shapeError('must be "#rrggbb" or [r, g, b]') }),
  );

export const white = (): Vec3 => [1, 1, 1];

export const emissionShape = { color: color(intensity).default(white), intensity: intensity().default(1) };
/** Radiance `color * intensity` from the outside of a surface (version 2); absent = none. */
export const emission = z.strictObject(emissionShape).optional();
