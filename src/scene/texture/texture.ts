/**
 * Textures in the scene model (scene format version 3, "Textures"): a
 * material input that is an image instead of a constant,
 * `{"image", "channel", "scale", "uv", "cutoff"}`. Pure TypeScript: the
 * schema of each kind of input (a color, a scalar, a normal map), the
 * normalized `Texture` and the helpers the renderer, the exporter and the
 * page share. Decoding is decode.ts; the lookup's reference, bitmapLookup.ts.
 */
import * as z from 'zod';
import { color, shapeError, unit } from '../schemaParts';
import type { Vec3 } from '../types';
import type { UvTransform } from './bitmapLookup';

export type { UvTransform };

/** What a texture feeds: a color (RGB, 8-bit images sRGB-decoded), a scalar (one channel as stored) or a normal map (RGB as stored). */
export type TextureInput = 'color' | 'scalar' | 'normal';
export type Channel = 'r' | 'g' | 'b' | 'a';
export const CHANNELS: readonly Channel[] = ['r', 'g', 'b', 'a'];

/** A texture, every default filled in. */
export interface Texture {
  /** The file, as written in the scene (relative to the scene file's folder). */
  image: string;
  /** The channel a scalar input reads ("r" for colors and normal maps, which read RGB). */
  channel: Channel;
  /** Multiplies the filtered value: a number, or a color for color inputs; a normal map's glTF `normalTexture.scale`. */
  scale: number | Vec3;
  uv: UvTransform;
  /** Scalar inputs: the filtered value becomes 1 where it is at least `cutoff`, 0 below (glTF's alpha MASK). */
  cutoff?: number;
}

/** Whether a material input holds a texture (not a constant). */
export const isTexture = (value: unknown): value is Texture =>
  typeof value === 'object' && value !== null && !Array.isArray(value) && 'image' in value;

const angle = () => z.number().min(-1e6).max(1e6);
const pair = (error: string) => z.tuple([angle(), angle()], { error: shapeError(error) });
const uvShape = {
  offset: pair('must be [u, v]').default(() => [0, 0] as [number, number]),
  scale: pair('must be [u, v]').default(() => [1, 1] as [number, number]),
  rotation: angle().default(0),
};
const image = z.string().max(4096).refine((name) => name.length > 0, 'must name a file');
const uv = z.strictObject(uvShape).default(() => ({ offset: [0, 0] as [number, number], scale: [1, 1] as [number, number], rotation: 0 }));
const factor = () => z.number().min(0).max(1e6);

/** The keys of a texture object for each input, for typo suggestions. */
export const TEXTURE_KEYS: Readonly<Record<TextureInput, readonly string[]>> = {
  color: ['image', 'scale', 'uv'],
  scalar: ['image', 'channel', 'scale', 'uv', 'cutoff'],
  normal: ['image', 'scale', 'uv'],
};
export const UV_KEYS = Object.keys(uvShape);

const TEXTURE_SCHEMAS: Record<TextureInput, z.ZodType<Texture>> = {
  color: z
    .strictObject({ image, scale: z.union([factor(), color(factor)], { error: shapeError('must be a number or [r, g, b]') }).default(1), uv })
    .transform((t) => ({ ...t, channel: 'r' as const })),
  scalar: z.strictObject({
    image,
    channel: z.enum(CHANNELS as [Channel, ...Channel[]], { error: shapeError('must be "r", "g", "b" or "a"') }).default('r'),
    scale: factor().default(1),
    uv,
    cutoff: unit().optional(),
  }),
  normal: z
    .strictObject({ image, scale: z.number().min(-1e6).max(1e6).default(1), uv })
    .transform((t) => ({ ...t, channel: 'r' as const })),
};

/**
 * A material input that may be a texture: `constant` (a value's schema) or
 * a texture object of the input's kind, told apart by being an object (a
 * constant is a number, an array or a "#rrggbb" string). Errors name the
 * key inside the texture (`...roughness.channel: must be ...`).
 */
export function texturable<T extends z.ZodType>(constant: T, input: 'color' | 'scalar') {
  return either(constant, TEXTURE_SCHEMAS[input]);
}

/** A normal map: only a texture. */
export const normalMapSchema = () => TEXTURE_SCHEMAS.normal;

function either<T extends z.ZodType>(constant: T, texture: z.ZodType<Texture>) {
  return z.custom<unknown>((value) => value !== undefined).transform((value, ctx): z.output<T> | Texture => {
    const object = typeof value === 'object' && value !== null && !Array.isArray(value);
    const result = (object ? texture : constant).safeParse(value);
    if (result.success) return result.data as z.output<T> | Texture;
    // Raw issues (custom ones keep their own message): the scene schema's
    // messages (its error map) are made for them.
    for (const issue of result.error.issues) {
      const { message, ...raw } = issue as z.core.$ZodIssue & { input?: unknown };
      ctx.issues.push({ ...raw, ...(issue.code === 'custom' ? { message } : {}), input: raw.input ?? value } as never);
    }
    return z.NEVER;
  });
}

/** A texture as scene JSON, every value explicit. */
export function textureJson(t: Texture, input: TextureInput): Record<string, unknown> {
  const uv = { offset: [...t.uv.offset], scale: [...t.uv.scale], rotation: t.uv.rotation };
  const scale = Array.isArray(t.scale) ? [...t.scale] : t.scale;
  if (input !== 'scalar') return { image: t.image, scale, uv };
  return { image: t.image, channel: t.channel, scale, uv, ...(t.cutoff === undefined ? {} : { cutoff: t.cutoff }) };
}

/** The `scale` of a texture as a color (a number on every channel). */
export const scaleColor = (t: Texture): Vec3 => (Array.isArray(t.scale) ? [...t.scale] : [t.scale, t.scale, t.scale]) as Vec3;
