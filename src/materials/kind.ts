/**
 * What a material kind is: everything the renderer, the schema, the
 * exporter and the page need to know of it, in one object per kind
 * (src/materials/<kind>/kind.ts). The registry (registry.ts) lists the
 * kinds and derives from them what used to be written by hand for each:
 * the schema's choice by `type`, the record layouts and tags, the feature
 * switches, the GLSL dispatch, serialization, export and the page's
 * controls. Pure TypeScript (no GL, no DOM).
 *
 * A kind's GLSL file (`glsl`, a chunk name relative to src/shaders/)
 * defines, for `<type>` the kind's type:
 *   vec3 <type>Eval(Bsdf b, vec3 wo, vec3 wi, out float pdf)
 *       f(wo, wi) |cos wi| of the non-delta lobes, and the density of
 *       <type>SampleDirection drawing wi;
 *   vec3 <type>SampleDirection(Bsdf b, vec3 wo, vec3 u, vec2 circle, out bool isDelta, out vec3 deltaWeight)
 *       a direction (u.z picks a lobe, u.x and circle = unitCircle(u.y) a
 *       disk point); for a Dirac delta, isDelta and f |cos| / pdf; the zero
 *       vector: no sample;
 *   bool <type>HasNonDeltaLobe(Bsdf b)   light sampling can contribute;
 *   bool <type>IsDelta(Bsdf b)           every lobe is a Dirac delta (the guide buffers follow it);
 *   vec3 <type>DeltaTint(Bsdf b, vec3 wo, vec3 wi)  the guide buffers' tint of a delta event;
 *   vec3 <type>Albedo(Bsdf b)            the guide buffers' albedo of a non-delta surface;
 *   float <type>GuideWeight(Bsdf b)      how much the caustic guides may take over BSDF sampling;
 * reading its parameters with the generated `<Type>Params <type>Params(Bsdf b)`.
 * Directions are in the shading frame (+z the normal on the outside).
 */
import type * as z from 'zod';
import type { FieldType, RecordValues } from '../render/layout/records';
import type { XmlNode } from '../scene/mitsubaXml';
import type { Texture, TextureInput } from '../scene/texture/texture';
import type { Emission, Vec3 } from '../scene/types';

/** A material input that may be a texture (src/scene/texture/texture.ts). */
export interface TextureSlot {
  /** The material's key. */
  key: string;
  /** A color (RGB, 8-bit images sRGB-decoded) or a scalar (one channel as stored). */
  input: 'color' | 'scalar';
}

/** How the Mitsuba exporter writes a texture: a `bitmap` of the baked image (factor x texture, sRGB decoded, one channel for scalars) beside the XML. */
export interface MitsubaTextures {
  bitmap(name: string, texture: Texture, input: TextureInput): XmlNode;
}

/** Range of an index of refraction inside a solid (the scene format's, for every kind that has one). */
export const MIN_IOR = 1.01;
export const MAX_IOR = 4;

/** GGX lobes with alpha = r^2 below this are treated as ideal (delta) lobes, in every BSDF (as pbrt-v4 does). */
export const DELTA_ALPHA = 1e-3;

/** What every material has, whatever its kind. */
export interface MaterialBase {
  type: string;
  /** Absent: the surface emits nothing. */
  emission?: Emission;
}

/**
 * A control of the page's material panel, as data (src/app/materialControls.ts
 * builds it). `texturable`: the input may be a texture (one of the kind's
 * `textures`, its `opacity`): where the object has texture coordinates the
 * page shows a texture slot while it is one, and an image opened or dropped
 * on the control makes it one.
 */
export type MaterialControl =
  | { control: 'color'; key: string; label: string; texturable?: boolean }
  | { control: 'number'; key: string; label: string; min: number; max: number; step: number; texturable?: boolean }
  /** An input that is only ever a texture (a normal map): absent, or a texture slot. */
  | { control: 'texture'; key: string; label: string; input: TextureInput }
  | {
      control: 'choice';
      key: string;
      label: string;
      options: readonly string[];
      /** The option shown (default: the value at `key`). */
      get?: (m: never) => string;
      /** Applies an option (default: sets `key`). */
      set?: (m: never, option: string) => void;
    };

export interface MaterialKind<M extends MaterialBase = MaterialBase> {
  /** The `type` key of the scene format. */
  readonly type: M['type'];
  /** The scene-format version that brought the kind (a document must declare at least that). */
  readonly version: 1 | 2 | 3;
  /** Its name on the page's type picker. */
  readonly label: string;
  /** The zod schema of its keys besides `type` and `emission` (defaults included). */
  readonly shape: z.ZodRawShape;
  /** Cross-field checks of the parsed keys: [path key, message] per problem. */
  readonly check?: (parsed: Record<string, unknown>) => [string, string][];
  /** The normalized material from the parsed keys (emission is added by the registry). */
  readonly normalize: (parsed: Record<string, unknown>) => Omit<M, 'emission'>;
  /** Its keys besides `type` and `emission` as scene JSON: every value explicit, so parsing gives `m` back. */
  readonly json: (m: M) => Record<string, unknown>;
  /** Its parameters' record fields (packed after the header every material has). */
  readonly fields: readonly [string, FieldType][];
  /** The values of `fields`. */
  readonly pack: (m: M) => RecordValues;
  /** Its GLSL chunk (see the interface above), relative to src/shaders/. */
  readonly glsl: string;
  /**
   * Whether a material is the boundary of a solid (glass): both sides are
   * its own, so it is never made two-sided, and it cannot be the ground (a
   * plane has no inside).
   */
  readonly solid: (m: M) => boolean;
  /** When `solid` can be true, what makes it so, for the ground's error message (the kind's `type` in quotes, and when). */
  readonly solidWhen?: string;
  /** Mitsuba's BSDF for it (wrapped in `twosided` on meshes unless `solid`, and in the registry's `normalmap` and `mask` adapters). */
  readonly mitsuba: (m: M, textures: MitsubaTextures) => XmlNode;
  /**
   * The inputs that may be textures. Each gets a texture index in the
   * record (the registry's, after the kind's fields); the kind's own field
   * holds the constant, or the texture's scale, which surface.glsl
   * multiplies by the lookup. Only the kinds whose inputs are listed here
   * accept textures.
   */
  readonly textures?: readonly TextureSlot[];
  /** Its opacity (1: opaque), when the kind has one: a cut-out or see-through surface (Mitsuba's `mask`). */
  readonly opacity?: (m: M) => number | Texture;
  /** Whether its emission's color may be a texture (version 3). */
  readonly texturedEmission?: boolean;
  /** Its normal map, when the kind has one (Mitsuba's `normalmap`). */
  readonly normalMap?: (m: M) => Texture | undefined;
  /**
   * The vec3 field a mesh's vertex colors multiply (glTF COLOR_0), when the
   * kind takes them: its base color, after the texture lookup (surface.glsl
   * evalMaterial). Only file materials turn them on (fileMaterials.ts).
   */
  readonly vertexColorKey?: string;
  /** The page's controls for its keys. */
  readonly controls: readonly MaterialControl[];
  /** What switching `current` (of another kind) to this kind gives; the registry keeps the emission. */
  readonly fromOther: (current: { color?: Vec3; roughness?: number }) => Omit<M, 'emission'>;
  /**
   * For the caustic guides (src/render/causticGuides.ts): the weight of the
   * material's ideal-mirror lobe and that lobe's largest albedo channel;
   * null when it has no such lobe (or the guides should not aim at it).
   */
  readonly idealMirror?: (m: M) => { weight: number; albedo: number } | null;
}
