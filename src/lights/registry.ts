/**
 * The light kinds, and everything derived from their descriptions
 * (kind.ts), as src/materials/registry.ts does for materials: the Light
 * union, the schema of a `lights` entry by its `type`, version rules,
 * serialization and Mitsuba export, the emitter record (a header every
 * emitter has, then its kind's fields) and the planar-light record of the
 * area kinds, the HAS_<KIND>_LIGHT switches and the generated GLSL (the
 * Emitter struct, each kind's parameter reader, the sampling and pdf
 * dispatch).
 *
 * Adding a kind: a folder src/lights/<kind>/ with kind.ts (its LightKind),
 * <kind>.glsl (the functions listed in kind.ts) and its tests, and one line
 * in KINDS below. Emissive spheres, the environment map and emissive meshes
 * are emitters too (tags after the sphere's), written by packScene.
 */
import * as z from 'zod';
import { defineRecord, fieldRead, packRecord, type RecordLayout, type RecordValues } from '../render/layout/records';
import type { XmlNode } from '../scene/mitsubaXml';
import type { Vec3 } from '../scene/types';
import { directional, type DirectionalLight } from './directional/kind';
import { disk, type DiskLight } from './disk/kind';
import type { LightControl, LightKind, PlanarShape, SceneBounds } from './kind';
import { pointLight, type PointLight } from './point/kind';
import { rectangle, type RectangleLight } from './rectangle/kind';
import { sphere, type SphereLight } from './sphere/kind';
import { spot, type SpotLight } from './spot/kind';

export type { DirectionalLight, DiskLight, PointLight, RectangleLight, SphereLight, SpotLight };
export type Light = SphereLight | RectangleLight | DiskLight | PointLight | SpotLight | DirectionalLight;
export type LightType = Light['type'];

/** Every kind; the first is the default (a light without `type`: version 1's sphere light), compiled into every program. */
export const LIGHT_KINDS: readonly LightKind<Light>[] = [sphere, rectangle, disk, pointLight, spot, directional] as unknown as LightKind<Light>[];
const DEFAULT_KIND = LIGHT_KINDS[0];
export const LIGHT_TYPE_NAMES: readonly string[] = LIGHT_KINDS.map((k) => k.type);
const BY_TYPE = new Map<string, LightKind<Light>>(LIGHT_KINDS.map((k) => [k.type, k]));
/** The description of a light's kind. */
export const lightKindOf = (l: { type: string }): LightKind<Light> => BY_TYPE.get(l.type)!;

// ---------------------------------------------------------------- schema

const schemas = new Map<string, z.ZodType<unknown>>(
  LIGHT_KINDS.map((kind) => {
    const type = kind === DEFAULT_KIND ? z.literal(kind.type).default(kind.type) : z.literal(kind.type);
    const schema = z.strictObject({ type, ...kind.shape }).superRefine((parsed, ctx) => {
      for (const [key, message] of kind.check?.(parsed) ?? []) ctx.addIssue({ code: 'custom', path: [key], message });
    });
    return [kind.type, schema as z.ZodType<unknown>] as const;
  }),
);

/** The schema of a light whose `type` is `type` (undefined: the default kind); undefined for an unknown type. */
export function lightSchema(type: unknown): z.ZodType<unknown> | undefined {
  return schemas.get(type === undefined ? DEFAULT_KIND.type : (type as string));
}
export const UNKNOWN_LIGHT_TYPE_MESSAGE = `must be ${LIGHT_TYPE_NAMES.map((t) => `"${t}"`).join(' or ')}`;
/** Every key of any kind, for typo suggestions. */
export const LIGHT_KEYS: readonly string[] = [...new Set(['type', ...LIGHT_KINDS.flatMap((k) => Object.keys(k.shape))])];

/** A fresh normalized light from what its schema parsed (-0 becomes 0). */
export function normalizeLight(parsed: Record<string, unknown>): Light {
  return clean(lightKindOf(parsed as { type: string }).normalize(parsed)) as Light;
}

function clean(value: unknown): unknown {
  if (typeof value === 'number') return value === 0 ? 0 : value;
  if (Array.isArray(value)) return value.map(clean);
  if (value && typeof value === 'object') return Object.fromEntries(Object.entries(value).map(([k, v]) => [k, clean(v)]));
  return value;
}

// ---------------------------------------------------------------- versions, JSON, export, page

export const lightVersion = (l: Light): 1 | 2 | 3 => lightKindOf(l).version;
/** The version that brought the kind named `type` (undefined: the default kind; unknown types: none). */
export function lightTypeVersion(type: unknown): number | undefined {
  return (type === undefined ? DEFAULT_KIND : BY_TYPE.get(type as string))?.version;
}
/** Scene JSON of a light, every value explicit; a document before version 3 has no `type` key (only sphere lights). */
export function lightJson(l: Light, version: number): Record<string, unknown> {
  const keys = lightKindOf(l).json(l);
  return version < 3 ? keys : { type: l.type, ...keys };
}
export const lightMitsuba = (l: Light): XmlNode => lightKindOf(l).mitsuba(l);
export const lightPower = (l: Light, bounds: SceneBounds): number => lightKindOf(l).power(l, bounds);
export const lightExtent = (l: Light) => lightKindOf(l).extent(l);
export const lightReach = (l: Light) => lightKindOf(l).reach(l);
export const lightSphere = (l: Light) => lightKindOf(l).sphere?.(l) ?? null;
export const lightArea = (l: Light): PlanarShape | null => lightKindOf(l).area?.(l) ?? null;
export const lightEmitted = (l: Light): Vec3 => lightKindOf(l).emitted(l);
export const lightControls = (l: Light): readonly LightControl[] => lightKindOf(l).controls;
export const lightLabel = (type: string) => BY_TYPE.get(type)?.label ?? type;
/** A new light of kind `type` near `target` (the page's "+ Light"). */
export const createLight = (type: LightType, target: Vec3): Light => BY_TYPE.get(type)!.create(target);
/** A light's position, if it has one (a directional light has none). */
export const lightPosition = (l: Light): Vec3 | null => ('position' in l ? l.position : null);

// ---------------------------------------------------------------- records

const upperName = (type: string) => type.replace(/([a-z])([A-Z])/g, '$1_$2').toUpperCase();
const capitalized = (type: string) => type[0].toUpperCase() + type.slice(1);

/**
 * Emitter tags (Emitter.kind in GLSL): the sphere (sphere lights and
 * emissive spheres), the environment map and emissive meshes keep version
 * 2's tags; the other light kinds follow.
 */
export const EMITTER_KINDS: Readonly<Record<string, number>> = {
  sphere: 0,
  environment: 1,
  mesh: 2,
  ...Object.fromEntries(LIGHT_KINDS.slice(1).map((k, i) => [k.type, 3 + i])),
};

/**
 * What every emitter record has: the radiance (or intensity, or
 * irradiance) it emits, its tag, and for
 * spheres the sphere, for meshes the mesh and its emissive-triangle slots
 * (lights/mesh_emitter.glsl), for area lights the planar-light slot.
 */
const HEADER_FIELDS: [string, 'vec3' | 'float' | 'int'][] = [
  ['radiance', 'vec3'], ['kind', 'int'], ['primitive', 'int'], ['first', 'int'], ['count', 'int'],
];
const HEADER_LAYOUT = defineRecord('EmitterHeader', HEADER_FIELDS);
const LAYOUTS = new Map<string, RecordLayout>(LIGHT_KINDS.map((k) => [k.type, defineRecord(`${capitalized(k.type)}Emitter`, [...HEADER_FIELDS, ...k.fields])]));
/** Texels per emitter record: the largest kind's. */
export const EMITTER_TEXELS = Math.max(...[...LAYOUTS.values()].map((l) => l.texels));
/** The layout of an emitter record of light kind `type` (a sphere's: also emissive spheres'; any other emitter's header reads the same). */
export const emitterLayout = (type = DEFAULT_KIND.type): RecordLayout => ({ ...LAYOUTS.get(type)!, name: 'Emitter', texels: EMITTER_TEXELS });

/** An emitter record: its header, and `params` (the fields of light kind `type`, when given). */
export function packEmitter(header: { radiance?: Vec3; kind: number; primitive?: number; first?: number; count?: number }, type?: string, params: RecordValues = {}): Float32Array {
  const layout = type ? LAYOUTS.get(type)! : HEADER_LAYOUT;
  const out = new Float32Array(EMITTER_TEXELS * 4);
  out.set(packRecord(layout, { ...header, ...params } as RecordValues));
  return out;
}
/** The record of a light of the `lights` list (`primitive`: its sphere or planar-light slot). */
export function packLightEmitter(l: Light, primitive: number): Float32Array {
  const kind = lightKindOf(l);
  return packEmitter({ radiance: lightEmitted(l), kind: EMITTER_KINDS[l.type], primitive }, l.type, kind.pack(l));
}
/** A record read back into its header and (for a light kind) its fields, for tests and tools. */
export function unpackEmitter(record: Float32Array): Record<string, number | number[] | string> {
  const tag = record[3];
  const type = Object.keys(EMITTER_KINDS).find((t) => EMITTER_KINDS[t] === tag) ?? String(tag);
  const layout = LAYOUTS.get(type) ?? HEADER_LAYOUT;
  const out: Record<string, number | number[] | string> = { type };
  for (const f of layout.fields) {
    const at = f.texel * 4 + f.offset;
    out[f.name] = f.type === 'vec3' ? Array.from(record.subarray(at, at + 3)) : record[at];
  }
  return out;
}

/**
 * An area light's shape in the planar-light table, which the closest-hit
 * and shadow queries loop over (scene/intersect.glsl): centre, half-axes,
 * its emitter tag, its emitter-only material and its slot in the emitter
 * table (-1: it emits nothing).
 */
export const PLANAR_LIGHT = defineRecord('PlanarLight', [
  ['center', 'vec3'], ['kind', 'int'], ['u', 'vec3'], ['material', 'int'], ['v', 'vec3'], ['emitter', 'int'],
]);
export function packPlanarLight(l: Light, material: number, emitter: number): Float32Array {
  const shape = lightArea(l)!;
  return packRecord(PLANAR_LIGHT, { center: shape.center, u: shape.u, v: shape.v, kind: EMITTER_KINDS[l.type], material, emitter });
}

/**
 * A sphere around an area light's shape (its centre and the half-diagonal
 * of its half-axes, which holds every corner of the rectangle they span and
 * so any shape inside it): the queries test it before the shape.
 */
export function planarBound(l: Light): [number, number, number, number] {
  const { center, u, v } = lightArea(l)!;
  const r = Math.hypot(...u, ...v);
  // Padded (0.1%) so that rounding in the shader's segment test never culls a ray through the rim.
  return [center[0], center[1], center[2], r * (1 + 1e-3) + 1e-7];
}

// ---------------------------------------------------------------- program variants

/** The kinds (besides the default, always compiled) whose code a scene with these lights needs. */
export function lightFeatures(lights: Iterable<Light>): string[] {
  const used = new Set<string>();
  for (const l of lights) if (l.type !== DEFAULT_KIND.type) used.add(l.type);
  return LIGHT_TYPE_NAMES.filter((t) => used.has(t));
}
export const ALL_LIGHT_FEATURES: readonly string[] = LIGHT_TYPE_NAMES.filter((t) => t !== DEFAULT_KIND.type);
const guardOf = (k: LightKind<Light>) => `HAS_${upperName(k.type)}_LIGHT`;

/** HAS_<KIND>_LIGHT per kind, HAS_PLANAR_LIGHTS (any area kind: their shapes are intersected), and the emitter texels the loader fetches. */
export function lightFeatureDefines(features: readonly string[]): Record<string, number> {
  const used = [DEFAULT_KIND, ...features.map((t) => BY_TYPE.get(t)!)];
  return {
    ...Object.fromEntries(LIGHT_KINDS.filter((k) => k !== DEFAULT_KIND).map((k) => [guardOf(k), features.includes(k.type) ? 1 : 0])),
    HAS_PLANAR_LIGHTS: used.some((k) => k.area) ? 1 : 0,
    EMITTER_FETCHED_TEXELS: Math.max(...used.map((k) => LAYOUTS.get(k.type)!.texels)),
  };
}

/** EMITTER_<TAG> and the record's size. */
export function lightDefines(): Record<string, number> {
  return { ...Object.fromEntries(Object.entries(EMITTER_KINDS).map(([t, tag]) => [`EMITTER_${upperName(t)}`, tag])), EMITTER_TEXELS };
}

/** The kinds' GLSL chunks, in LIGHT_KINDS order, and the switch each but the default's is compiled under. */
export const LIGHT_CHUNK_NAMES: readonly string[] = LIGHT_KINDS.map((k) => k.glsl);
export const LIGHT_CHUNK_GUARDS: ReadonlyMap<string, string> = new Map(LIGHT_KINDS.filter((k) => k !== DEFAULT_KIND).map((k) => [k.glsl, guardOf(k)]));

// ---------------------------------------------------------------- generated GLSL

const texelNames = (from: number) => Array.from({ length: EMITTER_TEXELS - from }, (_, i) => `t${i + from}`);

function paramsGlsl(kind: LightKind<Light>): string {
  const fields = LAYOUTS.get(kind.type)!.fields.slice(HEADER_FIELDS.length);
  if (fields.length === 0) return '';
  const name = `${capitalized(kind.type)}Light`;
  const members = fields.map((f) => `  ${f.type} ${f.name};`).join('\n');
  const reads = fields.map((f) => `  p.${f.name} = ${fieldRead(f, 'e.')};`).join('\n');
  return `struct ${name} {\n${members}\n};\n${name} ${kind.type}Light(Emitter e) {\n  ${name} p;\n${reads}\n  return p;\n}`;
}

/**
 * The Emitter record (its header's fields, then the raw texels of the
 * kinds' fields, fetched only as far as the program's kinds need), each
 * kind's parameter struct, the PlanarLight record and the planar shapes'
 * inside test.
 */
export function emitterGlsl(): string {
  const header = HEADER_LAYOUT.fields.map((f) => `  ${f.type} ${f.name};`).join('\n');
  const raw = texelNames(HEADER_LAYOUT.texels);
  const fetches = Array.from({ length: EMITTER_TEXELS }, (_, i) => {
    const fetch = `  vec4 t${i} = sceneData(first + ${i});`;
    return i < HEADER_LAYOUT.texels ? fetch : `#if EMITTER_FETCHED_TEXELS > ${i}\n${fetch}\n#else\n  vec4 t${i} = vec4(0.0);\n#endif`;
  });
  const assigns = [...HEADER_LAYOUT.fields.map((f) => `  e.${f.name} = ${fieldRead(f)};`), ...raw.map((t) => `  e.${t} = ${t};`)];
  const planarFields = PLANAR_LIGHT.fields.map((f) => `  ${f.type} ${f.name};`).join('\n');
  const planarFetches = Array.from({ length: PLANAR_LIGHT.texels }, (_, t) => `  vec4 t${t} = sceneData(first + ${t});`).join('\n');
  const planarAssigns = PLANAR_LIGHT.fields.map((f) => `  r.${f.name} = ${fieldRead(f)};`).join('\n');
  const areaKinds = LIGHT_KINDS.filter((k) => k.area);
  const insides = areaKinds.map((k) => `#if ${guardOf(k)}\n  if (kind == EMITTER_${upperName(k.type)}) return ${k.inside};\n#endif`);
  return [
    '// Generated from src/lights/registry.ts: do not edit.',
    `struct Emitter {\n${header}\n${raw.map((t) => `  vec4 ${t};`).join('\n')}\n};`,
    `Emitter readEmitter(int first) {\n${fetches.join('\n')}\n  Emitter e;\n${assigns.join('\n')}\n  return e;\n}`,
    ...LIGHT_KINDS.map(paramsGlsl).filter((s) => s !== ''),
    `struct PlanarLight {\n${planarFields}\n};`,
    `PlanarLight readPlanarLight(int first) {\n${planarFetches}\n  PlanarLight r;\n${planarAssigns}\n  return r;\n}`,
    `// Whether the plane point ab (in units of the half-axes) lies on a planar light of tag \`kind\`.\nbool planarLightInside(int kind, vec2 ab) {\n${insides.join('\n')}\n  return false;\n}`,
  ].join('\n');
}

/**
 * The sampling dispatch over the kinds besides the default (whose sample
 * sampleLight takes first; lights/lights.glsl) and the pdf of a hit on a
 * planar light. A kind the scene does not use is compiled out.
 */
export function lightDispatchGlsl(): string {
  const others = LIGHT_KINDS.filter((k) => k !== DEFAULT_KIND);
  const samples = others.map((k) => `#if ${guardOf(k)}\n  if (e.kind == EMITTER_${upperName(k.type)}) s = ${k.type}LightSample(e, x, u);\n#endif`);
  const pdfs = others.filter((k) => k.area).map((k) => `#if ${guardOf(k)}\n  if (kind == EMITTER_${upperName(k.type)}) return ${k.type}LightPdf(x, direction, hit);\n#endif`);
  return [
    '// Generated from src/lights/registry.ts: do not edit.',
    `// The sample of emitter e's kind, when it is one of the light kinds besides the sphere.\nvoid sampleLightKind(Emitter e, vec3 x, vec2 u, inout LightSample s) {\n${samples.join('\n')}\n}`,
    `// Density of light sampling drawing \`direction\` from x towards the planar light \`hit\`, once it picked that light.\nfloat planarLightPdf(vec3 x, vec3 direction, Hit hit) {\n  int kind = int(hit.geometry.y);\n${pdfs.join('\n')}\n  return 0.0;\n}`,
  ].join('\n');
}
