/**
 * What a light kind is: everything the schema, the packer, the shaders, the
 * exporter and the page need to know of it, in one object per kind
 * (src/lights/<kind>/kind.ts), as material kinds are (src/materials/kind.ts).
 * The registry (registry.ts) lists the kinds and derives the rest: the
 * schema's choice by `type`, the emitter record and its GLSL, the
 * HAS_<KIND>_LIGHT switches and the sampling dispatch, serialization,
 * export and version rules. Pure TypeScript (no GL, no DOM).
 *
 * A kind's GLSL file (`glsl`, a chunk name relative to src/shaders/)
 * defines, for `<type>` the kind's type:
 *   LightSample <type>LightSample(Emitter e, vec3 x, vec2 u)
 *       a direction from x towards the light (u: two uniform numbers), the
 *       distance along it, the radiance arriving at x, and the density in
 *       solid angle at x (emitter choice excluded); `delta` for a Dirac
 *       delta (pdf 1: never found by BSDF sampling); pdf 0: no sample;
 * reading its parameters with the generated `<Type>Light <type>Light(Emitter e)`.
 * Area kinds (`area` set: shapes in the planar-light table that rays hit;
 * `inside` the GLSL test of a point on their plane) also define
 *   float <type>LightPdf(vec3 x, vec3 direction, Hit hit)
 *       the density, in solid angle at x, of <type>LightSample drawing the
 *       direction towards `hit` (a hit on the shape), once the light is
 *       picked (lights/lights.glsl multiplies in the choice).
 */
import type * as z from 'zod';
import type { FieldType, RecordValues } from '../render/layout/records';
import type { XmlNode } from '../scene/mitsubaXml';
import type { Vec3 } from '../scene/types';

/** What every light has, whatever its kind. */
export interface LightBase {
  type: string;
  color: Vec3;
}

/** A planar shape of an area light: centre and the two half-axes (u along local x, v along local z); it emits towards cross(u, v). */
export interface PlanarShape {
  center: Vec3;
  u: Vec3;
  v: Vec3;
  /** Its area. */
  area: number;
}

/**
 * Where a light can send light, and about how much: the choice of emitter
 * at a shading point (src/render/lightChoice.ts) weighs each emitter by the
 * irradiance this predicts and gives it probability 0 only in a region
 * where it says none can arrive, so it must never say so wrongly.
 */
export interface LightReach {
  /** A sphere holding what emits (radius 0: a point); null: at infinity, the same from every point. */
  bound: { center: Vec3; radius: number } | null;
  /** Luminance of the irradiance it gives a point facing it at distance 1 (at infinity: its irradiance). */
  strength: number;
  /** A one-sided planar emitter's normal: it lights only points in front of the plane through bound.center. */
  front?: Vec3;
  /** A spot's cone: it lights only points within acos(cosCutoff) of `axis` from bound.center. */
  cone?: { axis: Vec3; cosCutoff: number };
}

/** What a light's power and export may need of the rest of the scene. */
export interface SceneBounds {
  /** Radius of a sphere around the scene's objects and camera (at least 1), as pbrt-v4 bounds a directional light. */
  radius: number;
}

/** A control of the page's light panel, as data. */
export type LightControl =
  | { control: 'color'; key: string; label: string }
  | { control: 'number'; key: string; label: string; min: number; max: number; step: number }
  | { control: 'vector'; key: string; label: string };

export interface LightKind<L extends LightBase = LightBase> {
  /** The `type` key of the scene format. */
  readonly type: L['type'];
  /** The scene-format version that brought the kind. */
  readonly version: 1 | 2 | 3;
  /** Its name on the page's "+ Light" menu. */
  readonly label: string;
  /** The zod schema of its keys besides `type` (defaults included). */
  readonly shape: z.ZodRawShape;
  /** Cross-field checks of the parsed keys: [path key, message] per problem. */
  readonly check?: (parsed: Record<string, unknown>) => [string, string][];
  /** The normalized light from the parsed keys. */
  readonly normalize: (parsed: Record<string, unknown>) => L;
  /** Its keys besides `type` as scene JSON: every value explicit. */
  readonly json: (l: L) => Record<string, unknown>;
  /** A light of this kind for the page's "+ Light", placed around `target`. */
  readonly create: (target: Vec3) => L;
  /** Its parameters' emitter-record fields (after the header every emitter has). */
  readonly fields: readonly [string, FieldType][];
  /** The values of `fields`. */
  readonly pack: (l: L) => RecordValues;
  /** The radiance (area kinds), intensity (point, spot) or irradiance (directional) the record's header carries. */
  readonly emitted: (l: L) => Vec3;
  /** Its GLSL chunk (see the interface above), relative to src/shaders/. */
  readonly glsl: string;
  /** A Dirac delta: reached only by next-event estimation (never seen, never hit). */
  readonly delta: boolean;
  /** An area light's planar shape (rays hit it; it emits towards cross(u, v)). */
  readonly area?: (l: L) => PlanarShape;
  /** An area light's GLSL test that the plane point `vec2 ab` (in units of the half-axes u and v) lies on the shape. */
  readonly inside?: string;
  /** A sphere light's geometry (the sphere table holds it). */
  readonly sphere?: (l: L) => { center: Vec3; radius: number };
  /** Emitted power (luminance-weighted, as for the other emitters): the emitter choice is in proportion to it. */
  readonly power: (l: L, bounds: SceneBounds) => number;
  /** Where and how strongly it lights (LightReach), for the choice of emitter at a shading point. */
  readonly reach: (l: L) => LightReach;
  /** Where it is and how far it reaches (for the scene's extent); null: at infinity. */
  readonly extent: (l: L) => { center: Vec3; radius: number } | null;
  /** Mitsuba's shape or emitter for it. */
  readonly mitsuba: (l: L) => XmlNode;
  /** The page's controls for its keys. */
  readonly controls: readonly LightControl[];
  /**
   * What the page's aim handle drags (src/app/lightHandles.ts): its
   * `target` point, its `rotation` (the emitting axis, local -y, turned the
   * least way), or its `direction`; none when absent. A kind with a
   * `position` key also has a move handle.
   */
  readonly aim?: 'target' | 'rotation' | 'direction';
}
