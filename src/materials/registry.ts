/**
 * The material kinds, and everything derived from their descriptions
 * (kind.ts): the Material union, the schema of a material by its `type`,
 * the record layouts and tags, the program variants' switches, the
 * generated GLSL (the Material record, each kind's parameter struct, the
 * BSDF dispatch), serialization, the Mitsuba export and version rules.
 *
 * Adding a kind: a folder src/materials/<kind>/ with kind.ts (its
 * MaterialKind), <kind>.glsl (the functions listed in kind.ts) and its
 * tests, and one line in KINDS below. Nothing else names a kind.
 */
import * as z from 'zod';
import { defineRecord, fieldRead, packRecord, type RecordLayout } from '../render/layout/records';
import { el, float } from '../scene/mitsubaXml';
import { emission, emissionShape, intensity } from '../scene/schemaParts';
import { color } from '../scene/schemaParts';
import { isTexture, scaleColor, texturable, textureJson, type Texture, type TextureInput } from '../scene/texture/texture';
import type { Emission, Vec3 } from '../scene/types';
import { conductor, type ConductorMaterial } from './conductor/kind';
import { dielectric, type DielectricMaterial } from './dielectric/kind';
import type { MaterialControl, MaterialKind, MitsubaTextures } from './kind';
import { principled, type PrincipledMaterial } from './principled/kind';
import { standard, type StandardMaterial } from './standard/kind';

export type { ConductorMaterial, DielectricMaterial, PrincipledMaterial, StandardMaterial };
export type Material = StandardMaterial | DielectricMaterial | ConductorMaterial | PrincipledMaterial;
export type MaterialType = Material['type'];

/**
 * Every kind; the first is the default (a material without `type`, the
 * version-1 material) and is compiled into every program: the BSDF
 * dispatch falls through to it.
 */
export const KINDS: readonly MaterialKind<Material>[] = [standard, dielectric, conductor, principled] as unknown as MaterialKind<Material>[];
const DEFAULT_KIND = KINDS[0];
export const MATERIAL_TYPE_NAMES: readonly string[] = KINDS.map((k) => k.type);

const BY_TYPE = new Map<string, MaterialKind<Material>>(KINDS.map((kind) => [kind.type, kind]));
/** The description of a material's kind. */
export const kindOf = (m: { type: string }): MaterialKind<Material> => BY_TYPE.get(m.type)!;

/** The default material: the default kind's defaults (an empty material object). */
export function defaultMaterial(): Material {
  return normalizeMaterial(materialSchema(DEFAULT_KIND.type)!.parse({}) as Record<string, unknown>);
}

// ---------------------------------------------------------------- schema

/** An emission whose color may be a texture (the kinds with texturedEmission). */
const texturedEmission = z.strictObject({ ...emissionShape, color: texturable(color(intensity), 'color').default((): Vec3 => [1, 1, 1]) }).optional();

const schemas = new Map<string, z.ZodType<unknown>>(
  KINDS.map((kind) => {
    const type = kind === DEFAULT_KIND ? z.literal(kind.type).default(kind.type) : z.literal(kind.type);
    const schema = z.strictObject({ type, ...kind.shape, emission: kind.texturedEmission ? texturedEmission : emission }).superRefine((parsed, ctx) => {
      for (const [key, message] of kind.check?.(parsed) ?? []) ctx.addIssue({ code: 'custom', path: [key], message });
    });
    return [kind.type, schema as z.ZodType<unknown>] as const;
  }),
);

/** The schema of a material whose `type` is `type` (undefined: the default kind); undefined for an unknown type. */
export function materialSchema(type: unknown): z.ZodType<unknown> | undefined {
  return schemas.get(type === undefined ? DEFAULT_KIND.type : (type as string));
}

/** The message for a `type` no kind has. */
export const UNKNOWN_TYPE_MESSAGE = `must be ${MATERIAL_TYPE_NAMES.map((t) => `"${t}"`).join(' or ')}`;

/** Every key of any kind, for typo suggestions. */
export const MATERIAL_KEYS: readonly string[] = [...new Set(['type', ...KINDS.flatMap((k) => Object.keys(k.shape)), 'emission'])];

/** A fresh normalized material from what its schema parsed (-0 becomes 0, emission copied). */
export function normalizeMaterial(parsed: Record<string, unknown>): Material {
  const kind = kindOf(parsed as { type: string });
  const material = clean(kind.normalize(parsed)) as Material;
  const e = parsed.emission as { color: Vec3 | Texture; intensity: number } | undefined;
  if (e && isTexture(e.color)) {
    const texture = clean(e.color) as Texture;
    material.emission = { color: scaleColor(texture), intensity: clean(e.intensity) as number, texture };
  } else if (e) material.emission = { color: clean(e.color) as Vec3, intensity: clean(e.intensity) as number };
  return material;
}

/** A deep copy of plain JSON-like data with -0 turned into 0. */
function clean(value: unknown): unknown {
  if (typeof value === 'number') return value === 0 ? 0 : value;
  if (Array.isArray(value)) return value.map(clean);
  if (value && typeof value === 'object') return Object.fromEntries(Object.entries(value).map(([k, v]) => [k, clean(v)]));
  return value;
}

/** Whether the ground may have this material: not the boundary of a solid (a plane has no inside). */
export const allowedOnGround = (m: Material) => !kindOf(m).solid(m);
/** What the ground's material must not be, per kind that can be a solid's boundary. */
export const SOLID_DESCRIPTIONS: readonly string[] = KINDS.flatMap((k) => (k.solidWhen ? [k.solidWhen] : []));

// ---------------------------------------------------------------- versions and JSON

/** The scene-format version a material needs: its kind's, and 2 for emission. */
export const materialVersion = (m: Material): 1 | 2 | 3 => Math.max(kindOf(m).version, m.emission ? 2 : 1) as 1 | 2 | 3;

/** The version that brought the kind named `type` (undefined: the default kind; unknown types: none). */
export function typeVersion(type: unknown): number | undefined {
  return (type === undefined ? DEFAULT_KIND : BY_TYPE.get(type as string))?.version;
}

/** Scene JSON of a material, every value explicit; a version-1 document has no `type` key. */
export function materialJson(m: Material, version: number): Record<string, unknown> {
  const keys = kindOf(m).json(m);
  const color = m.emission?.texture ? textureJson(m.emission.texture, 'color') : [...(m.emission?.color ?? [])];
  const e = m.emission ? { emission: { color, intensity: m.emission.intensity } } : {};
  return version === 1 ? keys : { type: m.type, ...keys, ...e };
}

// ---------------------------------------------------------------- Mitsuba

/** For materials without textures: any texture is an error. */
export const NO_MITSUBA_TEXTURES: MitsubaTextures = {
  bitmap: (name) => {
    throw new Error(`the Mitsuba export of a texture (${name}) needs the exporter's image baking`);
  },
};

/**
 * Mitsuba's BSDF of a material: the kind's, inside the `normalmap` adapter
 * when it has a normal map, `twosided` on a mesh unless the boundary of a
 * solid (the format's sidedness rule: so the back side keeps the normal
 * map's tilt), and `mask` outermost when it is not opaque.
 */
export function materialBsdf(m: Material, textures: MitsubaTextures = NO_MITSUBA_TEXTURES, onMesh = false) {
  const kind = kindOf(m);
  let bsdf = kind.mitsuba(m, textures);
  const normalMap = kind.normalMap?.(m);
  if (normalMap) bsdf = el('bsdf', { type: 'normalmap' }, [textures.bitmap('normalmap', normalMap, 'normal'), bsdf]);
  if (onMesh && !kind.solid(m)) bsdf = el('bsdf', { type: 'twosided' }, [bsdf]);
  const opacity = kind.opacity?.(m) ?? 1;
  if (opacity !== 1) bsdf = el('bsdf', { type: 'mask' }, [isTexture(opacity) ? textures.bitmap('opacity', opacity, 'scalar') : float('opacity', opacity), bsdf]);
  return bsdf;
}
/** ... on a mesh. */
export const meshBsdf = (m: Material, textures: MitsubaTextures = NO_MITSUBA_TEXTURES) => materialBsdf(m, textures, true);

// ---------------------------------------------------------------- textures

/** A texture a material reads, with its key and the input it feeds. */
export interface MaterialTexture {
  /** Its slot: a key of the kind's, or "emission" (the emission's color). */
  key: string;
  /** Where it is in the material's JSON (["emission", "color"] for the emission's). */
  path: string[];
  texture: Texture;
  input: TextureInput;
}

/** The textures of a material: its kind's texture slots that hold one, its opacity's and its normal map. */
export function materialTextures(m: Material): MaterialTexture[] {
  const kind = kindOf(m);
  const values = m as unknown as Record<string, unknown>;
  const out: MaterialTexture[] = [];
  for (const slot of kind.textures ?? []) {
    const value = values[slot.key];
    if (isTexture(value)) out.push({ key: slot.key, path: [slot.key], texture: value, input: slot.input });
  }
  const opacity = kind.opacity?.(m);
  if (isTexture(opacity)) out.push({ key: 'opacity', path: ['opacity'], texture: opacity, input: 'scalar' });
  const normalMap = kind.normalMap?.(m);
  if (normalMap) out.push({ key: 'normalMap', path: ['normalMap'], texture: normalMap, input: 'normal' });
  if (m.emission?.texture) out.push({ key: 'emission', path: ['emission', 'color'], texture: m.emission.texture, input: 'color' });
  return out;
}

/** The switch of a kind's texture slot (HAS_TEXTURE_<KIND>_<KEY>): compiled only when some material textures it. */
export const textureSlotDefine = (type: string, key: string) => `HAS_TEXTURE_${upperName(type)}_${upperName(key)}`;

/** The texture slots a scene's materials use, as their switches' names. */
export function textureSlotFeatures(materials: Iterable<Material>): string[] {
  const used = new Set<string>();
  for (const m of materials) for (const t of materialTextures(m)) used.add(textureSlotDefine(m.type, t.key));
  return [...used].sort();
}

/** Every texture slot's switch, 1 where `used` names it. */
export function textureSlotDefines(used: readonly string[]): Record<string, number> {
  const all = KINDS.flatMap((k) => [...(k.textures ?? []).map((slot) => slot.key), ...(k.texturedEmission ? ['emission'] : [])].map((key) => textureSlotDefine(k.type, key)));
  return Object.fromEntries(all.map((name) => [name, used.includes(name) ? 1 : 0]));
}

/** A material's opacity as a number (a texture's: its scale, the largest it can be). */
export function materialOpacityFactor(m: Material): number {
  const opacity = kindOf(m).opacity?.(m) ?? 1;
  return isTexture(opacity) ? (opacity.scale as number) : opacity;
}

/** Whether a material lets light through anywhere (opacity below 1, or an opacity texture). */
export function materialSeeThrough(m: Material): boolean {
  const opacity = kindOf(m).opacity?.(m) ?? 1;
  return isTexture(opacity) || opacity < 1;
}

// ---------------------------------------------------------------- page

/** The page's controls of a material's kind. */
export const materialControls = (m: Material): readonly MaterialControl[] => kindOf(m).controls;
export const kindLabel = (type: string) => BY_TYPE.get(type)?.label ?? type;
/** What a control's input takes when it is a texture (null: never one). */
export function controlTextureInput(control: MaterialControl): TextureInput | null {
  if (control.control === 'texture') return control.input;
  if (control.control === 'choice' || !control.texturable) return null;
  return control.control === 'color' ? 'color' : 'scalar';
}

/** The value of input `key` of `m`'s kind when the scene leaves it out (its schema's default; undefined for an optional one). */
export function inputDefault(m: Material, key: string): unknown {
  const schema = kindOf(m).shape[key] as z.ZodType | undefined;
  const parsed = schema?.safeParse(undefined);
  return parsed?.success ? parsed.data : undefined;
}

/** The key of a material's main color (its kind's first color control: `color`, or a principled material's `baseColor`). */
export const mainColorKey = (m: Material): string => kindOf(m).controls.find((c) => c.control === 'color')?.key ?? 'color';

/**
 * The material after switching `current` to kind `to`; emission is kept.
 * With `remembered` (the object's last material of that kind) its
 * parameters come back; otherwise the kind's `fromOther`.
 */
export function switchMaterialType(current: Material, to: MaterialType, remembered?: Material): Material {
  if (current.type === to) return structuredClone(current);
  const e = current.emission ? { emission: structuredClone(current.emission) } : {};
  if (remembered?.type === to) {
    const { emission: _dropped, ...parameters } = structuredClone(remembered);
    return { ...parameters, ...e } as Material;
  }
  // A texture stays behind: the other kinds' inputs may not take one.
  const from = current as { color?: unknown; roughness?: unknown };
  const color = Array.isArray(from.color) ? (from.color as Vec3) : undefined;
  const roughness = typeof from.roughness === 'number' ? from.roughness : undefined;
  return { ...(BY_TYPE.get(to)!.fromOther({ color, roughness }) as Material), ...e };
}

// ---------------------------------------------------------------- records

/**
 * A material record: texel 0 is [emission.rgb, tag | flags] for every kind;
 * the kind's fields follow. Tags are the kinds' indices in KINDS, then the
 * emitter-only material of the `lights`; flags sit above the tag's bits.
 */
const HEADER_FIELDS: [string, 'vec3' | 'int'][] = [['emission', 'vec3'], ['type', 'int']];
const upperName = (type: string) => type.replace(/([a-z])([A-Z])/g, '$1_$2').toUpperCase();
const capitalized = (type: string) => type[0].toUpperCase() + type.slice(1);

export const MATERIAL_TAGS: Readonly<Record<string, number>> = {
  ...Object.fromEntries(KINDS.map((k, i) => [k.type, i])),
  emitterOnly: KINDS.length,
};
/** The tag's bits of texel 0's w; the flags above them. */
const TAG_MASK = 15;
const FLAG_TWO_SIDED = 16;

const LAYOUTS = new Map<string, RecordLayout>(KINDS.map((k) => [k.type, defineRecord(`${capitalized(k.type)}Material`, [...HEADER_FIELDS, ...k.fields])]));

/** Texture-slot keys of a kind whose inputs may be textures: its slots, then its opacity's and normal map's. */
const slotKeys = (k: MaterialKind<Material>) => [
  ...(k.textures ?? []).map((t) => t.key),
  ...(k.opacity ? ['opacity'] : []),
  ...(k.normalMap ? ['normalMap'] : []),
  ...(k.texturedEmission ? ['emission'] : []),
];
const textureField = (key: string) => `texture${key[0].toUpperCase()}${key.slice(1)}`;
/**
 * The record's surface inputs, for kinds that have any: after the kind's
 * fields, from a texel of their own (fetched only by programs whose scene
 * has textures or see-through materials): the opacity, then each slot's
 * texture index (-1: none; the texture table of textures/texture.glsl).
 */
const SURFACE_LAYOUTS = new Map<string, RecordLayout>(
  KINDS.filter((k) => slotKeys(k).length > 0).map((k) => [
    k.type,
    defineRecord(`${capitalized(k.type)}Surface`, [['opacity', 'float'], ...slotKeys(k).map((key): [string, 'float'] => [textureField(key), 'float'])]),
  ]),
);
/** Texels of a kind's record: its fields', then (withSurface) its surface inputs'. */
const recordTexels = (type: string, withSurface: boolean) => LAYOUTS.get(type)!.texels + (withSurface ? (SURFACE_LAYOUTS.get(type)?.texels ?? 0) : 0);
/** Texels per material record: the largest kind's. */
export const MATERIAL_TEXELS = Math.max(...KINDS.map((k) => recordTexels(k.type, true)));

/**
 * The record of a material. `twoSided`: the integrator turns the shading
 * frame towards the viewer (Mitsuba's `twosided`), written where the
 * material is on a mesh and is not a solid's boundary.
 */
export function packMaterial(m: Material, onMesh: boolean, textureIndex: (t: MaterialTexture) => number = noTextures): Float32Array {
  const kind = kindOf(m);
  const flags = onMesh && !kind.solid(m) ? FLAG_TWO_SIDED : 0;
  const e = m.emission;
  const emitted: Vec3 = e ? [e.color[0] * e.intensity, e.color[1] * e.intensity, e.color[2] * e.intensity] : [0, 0, 0];
  const layout = LAYOUTS.get(m.type)!;
  const record = packRecord(layout, { emission: emitted, type: MATERIAL_TAGS[m.type] + flags, ...kind.pack(m) });
  const out = new Float32Array(MATERIAL_TEXELS * 4);
  out.set(record);
  const surface = SURFACE_LAYOUTS.get(m.type);
  if (surface) {
    const opacity = kind.opacity?.(m) ?? 1;
    const indices: Record<string, number> = Object.fromEntries(slotKeys(kind).map((key) => [textureField(key), -1]));
    for (const t of materialTextures(m)) indices[textureField(t.key)] = textureIndex(t);
    out.set(packRecord(surface, { opacity: isTexture(opacity) ? (opacity.scale as number) : opacity, ...indices }), layout.texels * 4);
  }
  return out;
}
const noTextures = (t: MaterialTexture): number => {
  throw new Error(`packMaterial: no texture table for ${t.key}`);
};

/** A record read back into its kind's named fields (`type` the kind, or "emitterOnly"), for tests and tools. */
export function unpackMaterial(record: Float32Array): Record<string, number | number[] | string | boolean> {
  const word = record[3];
  const type = Object.keys(MATERIAL_TAGS).find((t) => MATERIAL_TAGS[t] === (word & TAG_MASK))!;
  const layout = LAYOUTS.get(type);
  const out: Record<string, number | number[] | string | boolean> = { type, twoSided: (word & FLAG_TWO_SIDED) !== 0, emission: Array.from(record.subarray(0, 3)) };
  for (const f of layout?.fields.slice(HEADER_FIELDS.length) ?? []) {
    const at = f.texel * 4 + f.offset;
    out[f.name] = f.type === 'vec3' ? Array.from(record.subarray(at, at + 3)) : record[at];
  }
  return out;
}

/** A `lights` entry: emits `radiance`, reflects nothing. */
export function packEmitterOnly(radiance: Vec3): Float32Array {
  const out = new Float32Array(MATERIAL_TEXELS * 4);
  out.set([...radiance, MATERIAL_TAGS.emitterOnly]);
  return out;
}

// ---------------------------------------------------------------- program variants

/** The kinds (besides the default, always compiled) whose code a scene with these materials needs. */
export function materialFeatures(materials: Iterable<Material>): string[] {
  const used = new Set<string>();
  for (const m of materials) if (m.type !== DEFAULT_KIND.type) used.add(m.type);
  return MATERIAL_TYPE_NAMES.filter((t) => used.has(t));
}
/** Every kind but the default: the test kernels compile them all. */
export const ALL_MATERIAL_FEATURES: readonly string[] = MATERIAL_TYPE_NAMES.filter((t) => t !== DEFAULT_KIND.type);

/**
 * HAS_<KIND> per kind, and how many texels of a record the loader fetches:
 * the largest used kind's, with its surface inputs only when the scene has
 * textures or see-through materials (`surfaceInputs`).
 */
export function materialFeatureDefines(features: readonly string[], surfaceInputs = false): Record<string, number> {
  const used = [DEFAULT_KIND.type, ...features];
  return {
    ...Object.fromEntries(KINDS.filter((k) => k !== DEFAULT_KIND).map((k) => [`HAS_${upperName(k.type)}`, features.includes(k.type) ? 1 : 0])),
    MATERIAL_FETCHED_TEXELS: Math.max(...used.map((t) => recordTexels(t, surfaceInputs))),
  };
}

/** MATERIAL_<TAG> and the record's constants. */
export function materialDefines(): Record<string, number> {
  return {
    ...Object.fromEntries(Object.entries(MATERIAL_TAGS).map(([type, tag]) => [`MATERIAL_${upperName(type)}`, tag])),
    MATERIAL_TEXELS,
    MATERIAL_TAG_MASK: TAG_MASK,
    MATERIAL_FLAG_TWO_SIDED: FLAG_TWO_SIDED,
  };
}

/**
 * The surface inputs in GLSL (compiled under HAS_SURFACE_INPUTS, after
 * textures/texture.glsl): a material's opacity and normal-map texture, and
 * its textured BSDF inputs multiplied in, at a point.
 */
export function surfaceInputsGlsl(): string {
  const kinds = KINDS.filter((k) => SURFACE_LAYOUTS.has(k.type));
  const surfaceField = (k: MaterialKind<Material>, name: string) => {
    const f = SURFACE_LAYOUTS.get(k.type)!.fields.find((x) => x.name === name)!;
    return fieldRead({ ...f, texel: f.texel + LAYOUTS.get(k.type)!.texels }, 'm.');
  };
  const perKind = (body: (k: MaterialKind<Material>) => string[], otherwise: string) =>
    [...kinds.map((k) => `  if (materialType(m) == MATERIAL_${upperName(k.type)}) {\n${body(k).map((l) => `    ${l}`).join('\n')}\n  }`), `  ${otherwise}`].join('\n');
  // Each slot compiled only where the scene textures it (SwiftShader runs masked blocks too).
  const apply = (k: MaterialKind<Material>) =>
    (k.textures ?? []).flatMap((slot) => {
      const field = LAYOUTS.get(k.type)!.fields.find((f) => f.name === slot.key)!;
      const lookup = slot.input === 'color' ? 'textureColor' : 'textureScalar';
      return [
        `#if ${textureSlotDefine(k.type, slot.key)}`,
        `{ int t = int(${surfaceField(k, textureField(slot.key))}); if (t >= 0) ${fieldRead(field, 'b.')} *= ${lookup}(t, uv); }`,
        '#endif',
      ];
    });
  const opacity = (k: MaterialKind<Material>) =>
    k.opacity
      ? [
          `float o = ${surfaceField(k, 'opacity')};`,
          // A see-through scene may have no texture (a constant opacity).
          '#if HAS_TEXTURES',
          `int t = int(${surfaceField(k, textureField('opacity'))});`,
          'if (t >= 0) o *= textureScalar(t, uv);',
          '#endif',
          'return o;',
        ]
      : ['return 1.0;'];
  const normalMap = (k: MaterialKind<Material>) => [`return ${k.normalMap ? `int(${surfaceField(k, textureField('normalMap'))})` : '-1'};`];
  const emissionAt = (k: MaterialKind<Material>) =>
    k.texturedEmission
      ? [
          `#if ${textureSlotDefine(k.type, 'emission')}`,
          `{ int t = int(${surfaceField(k, textureField('emission'))}); if (t >= 0) return materialEmission(m) * textureColor(t, uv); }`,
          '#endif',
          'return materialEmission(m);',
        ]
      : ['return materialEmission(m);'];
  return [
    '// Generated from src/materials/registry.ts: do not edit.',
    `// The opacity at uv (1: opaque).\nfloat materialOpacity(Material m, vec2 uv) {\n${perKind(opacity, 'return 1.0;')}\n}`,
    `// The normal map's texture (-1: none).\nint materialNormalMap(Material m) {\n${perKind(normalMap, 'return -1;')}\n}`,
    `// The emitted radiance at uv (the record's, times its texture where the color is one).\nvec3 materialEmissionAt(Material m, vec2 uv) {\n${perKind(emissionAt, 'return materialEmission(m);')}\n}`,
    `// The textured inputs of b (the record's constants, or their textures' scales) times their lookups at uv.\nvoid applyMaterialTextures(inout Bsdf b, Material m, vec2 uv) {\n${perKind((k) => [...apply(k), 'return;'], 'return;')}\n}`,
  ].join('\n');
}

/** The kinds' GLSL chunks, in KINDS order. */
export const MATERIAL_CHUNK_NAMES: readonly string[] = KINDS.map((k) => k.glsl);
/** The switch each chunk but the default kind's is compiled under (HAS_<KIND>). */
export const MATERIAL_CHUNK_GUARDS: ReadonlyMap<string, string> = new Map(KINDS.filter((k) => k !== DEFAULT_KIND).map((k) => [k.glsl, `HAS_${upperName(k.type)}`]));

// ---------------------------------------------------------------- generated GLSL

const texelNames = (from: number) => Array.from({ length: MATERIAL_TEXELS - from }, (_, i) => `t${i + from}`);

/**
 * applyVertexColor (compiled only under HAS_VERTEX_COLORS): the kinds with
 * a vertexColorKey multiply that field by the mesh's interpolated vertex
 * color; the others ignore it.
 */
function vertexColorGlsl(): string {
  const cases = KINDS.filter((k) => k.vertexColorKey).map((k) => {
    const field = LAYOUTS.get(k.type)!.fields.find((f) => f.name === k.vertexColorKey)!;
    return `  if (b.type == MATERIAL_${upperName(k.type)}) ${fieldRead(field, 'b.')} *= color;`;
  });
  return `#if HAS_VERTEX_COLORS\n// A mesh's vertex color at the hit multiplied into the kind's base color (glTF COLOR_0).\nvoid applyVertexColor(inout Bsdf b, vec3 color) {\n${cases.join('\n')}\n}\n#endif`;
}

/** The kind's parameter struct and its reader from a Bsdf's texels. */
function paramsGlsl(kind: MaterialKind<Material>): string {
  const layout = LAYOUTS.get(kind.type)!;
  const fields = layout.fields.slice(HEADER_FIELDS.length);
  const name = `${capitalized(kind.type)}Params`;
  const members = fields.map((f) => `  ${f.type} ${f.name};`).join('\n');
  const reads = fields.map((f) => `  p.${f.name} = ${fieldRead(f, 'b.')};`);
  return `struct ${name} {\n${members}\n};\n${name} ${kind.type}Params(Bsdf b) {\n  ${name} p;\n${reads.join('\n')}\n  return p;\n}`;
}

/**
 * The Material record as stored (its raw texels, read with as many fetches
 * as the program's kinds need), its header's accessors, the Bsdf (a kind's
 * parameters evaluated at a surface point: surface.glsl's evalMaterial) and
 * each kind's parameter struct.
 */
export function materialGlsl(): string {
  const texels = texelNames(0);
  const fetches = texels.map((t, i) => {
    const fetch = `  m.${t} = sceneData(first + ${i});`;
    return i < 2 ? fetch : `#if MATERIAL_FETCHED_TEXELS > ${i}\n${fetch}\n#else\n  m.${t} = vec4(0.0);\n#endif`;
  });
  return [
    '// Generated from src/materials/registry.ts: do not edit.',
    `struct Material {\n${texels.map((t) => `  vec4 ${t};`).join('\n')}\n};`,
    `Material readMaterial(int first) {\n  Material m;\n${fetches.join('\n')}\n  return m;\n}`,
    `// A record given as texels (the test kernels' uniform).\nMaterial materialOf(vec4 texels[MATERIAL_TEXELS]) {\n  Material m;\n${texels.map((t, i) => `  m.${t} = texels[${i}];`).join('\n')}\n  return m;\n}`,
    'vec3 materialEmission(Material m) { return m.t0.xyz; }',
    'int materialType(Material m) { return int(m.t0.w) & MATERIAL_TAG_MASK; }',
    'bool materialTwoSided(Material m) { return (int(m.t0.w) & MATERIAL_FLAG_TWO_SIDED) != 0; }',
    `struct Bsdf {\n  int type;\n  bool twoSided;\n${texelNames(1).map((t) => `  vec4 ${t};`).join('\n')}\n};`,
    `// The record's constant parameters (surface.glsl's evalMaterial starts from them).\nBsdf bsdfFromRecord(Material m) {\n  Bsdf b;\n  b.type = materialType(m);\n  b.twoSided = materialTwoSided(m);\n${texelNames(1).map((t) => `  b.${t} = m.${t};`).join('\n')}\n  return b;\n}`,
    vertexColorGlsl(),
    ...KINDS.map(paramsGlsl),
  ].join('\n');
}

interface DispatchedFunction {
  result: string;
  name: string;
  params: string;
  args: string;
}
const DISPATCHED: DispatchedFunction[] = [
  { result: 'vec3', name: 'Eval', params: 'Bsdf b, vec3 wo, vec3 wi, out float pdf', args: 'b, wo, wi, pdf' },
  {
    result: 'vec3',
    name: 'SampleDirection',
    params: 'Bsdf b, vec3 wo, vec3 u, vec2 circle, out bool isDelta, out vec3 deltaWeight',
    args: 'b, wo, u, circle, isDelta, deltaWeight',
  },
  { result: 'bool', name: 'HasNonDeltaLobe', params: 'Bsdf b', args: 'b' },
  { result: 'bool', name: 'IsDelta', params: 'Bsdf b', args: 'b' },
  { result: 'vec3', name: 'DeltaTint', params: 'Bsdf b, vec3 wo, vec3 wi', args: 'b, wo, wi' },
  { result: 'vec3', name: 'Albedo', params: 'Bsdf b', args: 'b' },
  { result: 'float', name: 'GuideWeight', params: 'Bsdf b', args: 'b' },
];

/**
 * The BSDF interface (bsdfEval, bsdfSampleDirection, ...): one dispatch on
 * the kind each. The code of a kind the scene does not use is compiled out
 * (HAS_<KIND>): SwiftShader runs every branch under lane masks, so unused
 * kinds would still cost their full price. The default kind is the
 * fall-through.
 */
export function bsdfDispatchGlsl(): string {
  const others = KINDS.filter((k) => k !== DEFAULT_KIND);
  const functions = DISPATCHED.map((f) => {
    const cases = others.map(
      (k) => `#if HAS_${upperName(k.type)}\n  if (b.type == MATERIAL_${upperName(k.type)}) return ${k.type}${f.name}(${f.args});\n#endif`,
    );
    return `${f.result} bsdf${f.name}(${f.params}) {\n${cases.join('\n')}\n  return ${DEFAULT_KIND.type}${f.name}(${f.args});\n}`;
  });
  return ['// Generated from src/materials/registry.ts: do not edit.', ...functions].join('\n');
}
