/**
 * Scene format versions 1 to 3: validation and normalization of untrusted input.
 * docs/scene-format.md documents every rule enforced here; keep them in step.
 *
 * `parseScene` is the only way JSON becomes a `Scene`. It reports every
 * problem at once, each with the JSON path of the offending value
 * (`spheres[2].material.roughness: must be <= 1`), and throws nothing but
 * `SceneError`, whatever the input.
 */
import * as z from 'zod';
import {
  allowedOnGround, defaultMaterial, KINDS, materialTextures, MATERIAL_KEYS, materialSchema, normalizeMaterial, SOLID_DESCRIPTIONS, UNKNOWN_TYPE_MESSAGE,
} from '../materials/registry';
import { LIGHT_KEYS, lightSchema, normalizeLight, UNKNOWN_LIGHT_TYPE_MESSAGE } from '../lights/registry';
import { MAX_BOUNCES, MAX_IMAGE_SIZE, MAX_LIGHTS, MAX_MESHES, MAX_SCENE_BYTES, MAX_SPHERES } from './limits';
import {
  color, coordinate, emissionShape, integer, intensity, length, MAX_COORDINATE, MAX_INTENSITY, point, shapeError, white,
} from './schemaParts';
import type { Camera, Environment, Ground, Light, Material, Mesh, Scene, Sphere, Vec3 } from './types';
import { versionIssues } from './version';
import { TEXTURE_KEYS, UV_KEYS } from './texture/texture';
import { SceneError, type SafeParseResult, type SceneIssue } from './issues';

export { MAX_COORDINATE, MAX_INTENSITY };
/** Largest explicit `camera.focusDistance` (more than any distance inside the coordinate box). */
export const MAX_FOCUS_DISTANCE = 1e7;
/** Shortest allowed `camera.up`, and closest allowed `camera.target` to `camera.position`. */
export const MIN_CAMERA_LENGTH = 1e-6;
/** At most this many issues are reported; one more issue at the root counts the rest. */
export const MAX_REPORTED_ISSUES = 100;

export { SceneError, formatIssue, type SceneIssue, type SafeParseResult } from './issues';

// ---------------------------------------------------------------- the schema

/** Array of at most `max` items; the length is checked before any item is looked at. */
const list = <T extends z.ZodType>(item: T, max: number, noun: string) =>
  z
    .array(z.unknown())
    .max(max, `at most ${max} ${noun}`)
    .pipe(z.array(item))
    .default(() => []);

/**
 * One of several object schemas, chosen by looking at the value (a material
 * by its `type`, an environment by its `map` key), so that errors name the
 * fields of the chosen kind instead of a failed union.
 */
function oneOf<T>(choose: (value: Record<string, unknown>) => z.ZodType<T> | string) {
  return z.custom<unknown>().transform((value, ctx): T => {
    const schema = isRecord(value) ? choose(value) : (z.strictObject({}) as unknown as z.ZodType<T>);
    if (typeof schema === 'string') {
      ctx.issues.push({ code: 'custom', path: ['type'], message: schema, input: value });
      return z.NEVER;
    }
    const result = schema.safeParse(value, { error: messageFor });
    if (result.success) return result.data;
    for (const issue of result.error.issues) ctx.issues.push({ ...issue, input: value } as never);
    return z.NEVER;
  });
}
/** A material by its `type` (absent = the default kind), through the kinds' registry. */
const anyMaterial = oneOf<Material>((value) => (materialSchema(value.type) as z.ZodType<Material> | undefined) ?? UNKNOWN_TYPE_MESSAGE);
const material = anyMaterial.default(defaultMaterial);
const materialKeys = MATERIAL_KEYS;

function isRecord(value: unknown): value is Record<string, unknown> {
  return typeof value === 'object' && value !== null && !Array.isArray(value);
}

const cameraShape = {
  position: point(),
  target: point(),
  up: point().default((): Vec3 => [0, 1, 0]),
  fov: z.number().gt(0).lt(180).default(40),
  aperture: z.number().min(0).max(MAX_COORDINATE).default(0),
  focusDistance: z.number().gt(0).max(MAX_FOCUS_DISTANCE).optional(),
};

/**
 * Runs a cross-field check when the object and the fields it reads parsed
 * cleanly, even if other fields did not, so that all errors show at once.
 */
const whenValid =
  (...keys: string[]) =>
  (payload: { issues: readonly { code?: string; path?: PropertyKey[] }[] }) =>
    payload.issues.every((issue) => {
      const key = issue.path?.[0];
      if (key === undefined) return issue.code === 'unrecognized_keys';
      return !keys.includes(String(key));
    });

const camera = z
  .strictObject(cameraShape)
  .refine((c) => distance(c.position, c.target) >= MIN_CAMERA_LENGTH, {
    path: ['target'],
    message: 'must differ from camera.position',
    when: whenValid('position', 'target'),
  })
  .refine((c) => Math.hypot(...c.up) >= MIN_CAMERA_LENGTH, {
    path: ['up'],
    message: 'must not be zero length',
    when: whenValid('up'),
  });

const imageShape = { width: integer(1, MAX_IMAGE_SIZE), height: integer(1, MAX_IMAGE_SIZE) };
const renderShape = { maxBounces: integer(0, MAX_BOUNCES).default(6) };
const environmentShape = { color: color(intensity).default(white), intensity: intensity().default(1) };
const mapEnvironmentShape = {
  map: z.string().min(1, 'must name a file').max(4096),
  intensity: intensity().default(1),
  rotation: z.number().min(-1e6).max(1e6).default(0),
};
/** The constant sky (version 1) or a map (version 2), told apart by the `map` key. */
const environment = oneOf<Environment>(
  (value) => ('map' in value ? z.strictObject(mapEnvironmentShape) : z.strictObject(environmentShape)) as z.ZodType<Environment>,
);
/** The ground is a plane: it has no inside (no solid's boundary, such as glass) and emits nothing. */
const groundMaterial = material.refine(allowedOnGround, {
  path: ['type'],
  message: `must not be ${SOLID_DESCRIPTIONS.join(' or ')} on the ground (a plane has no inside)`,
}).refine((m) => m.emission === undefined, { path: ['emission'], message: 'is not allowed on the ground' });
const groundShape = { height: coordinate().default(0), material: groundMaterial };
/** A light by its `type` (absent = the sphere light of version 1), through the light kinds' registry. */
const light = oneOf<Light>((value) => (lightSchema(value.type) as z.ZodType<Light> | undefined) ?? UNKNOWN_LIGHT_TYPE_MESSAGE);
/** Spheres have no texture coordinates (the format's rule), so no textures. */
const sphereMaterial = material.superRefine((m, ctx) => {
  for (const t of materialTextures(m)) ctx.addIssue({ code: 'custom', path: t.path, message: 'cannot be a texture on a sphere (spheres have no texture coordinates)' });
});
const sphereShape = { center: point(), radius: length(), material: sphereMaterial };
const positiveScale = () => z.number().gt(0).max(MAX_COORDINATE);
const meshShape = {
  file: z.string().min(1, 'must name a file').max(4096),
  material: anyMaterial.optional(),
  position: point().default((): Vec3 => [0, 0, 0]),
  rotation: z
    .tuple([z.number().min(-1e6).max(1e6), z.number().min(-1e6).max(1e6), z.number().min(-1e6).max(1e6)], {
      error: shapeError('must be [x, y, z] in degrees'),
    })
    .default((): Vec3 => [0, 0, 0]),
  scale: z
    .union([positiveScale(), z.tuple([positiveScale(), positiveScale(), positiveScale()])], {
      error: shapeError('must be a number > 0 or [x, y, z], each > 0'),
    })
    .default(1),
};

const sceneShape = {
  version: z.union([z.literal(1), z.literal(2), z.literal(3)], { error: shapeError('must be 1, 2 or 3') }).default(1),
  camera,
  image: z.strictObject(imageShape).default(() => ({ width: 640, height: 480 })),
  render: z.strictObject(renderShape).default(() => ({ maxBounces: 6 })),
  environment: environment.nullable().default(null),
  ground: z.strictObject(groundShape).nullable().default(null),
  lights: list(light, MAX_LIGHTS, 'lights'),
  spheres: list(z.strictObject(sphereShape), MAX_SPHERES, 'spheres'),
  meshes: list(z.strictObject(meshShape), MAX_MESHES, 'meshes'),
};
const sceneSchema = z.strictObject(sceneShape);

/** The JSON a scene document may hold (what `serializeScene` writes), derived from the schema. */
export type SceneJson = z.input<typeof sceneSchema>;

/** Keys allowed in each object, by path pattern ("[]" for any index), to suggest fixes for typos. */
const KNOWN_KEYS: Record<string, readonly string[]> = {
  '': Object.keys(sceneShape),
  camera: Object.keys(cameraShape),
  image: Object.keys(imageShape),
  render: Object.keys(renderShape),
  environment: [...Object.keys(environmentShape), ...Object.keys(mapEnvironmentShape)],
  ground: Object.keys(groundShape),
  'ground.material': materialKeys,
  'ground.material.emission': Object.keys(emissionShape),
  'lights[]': LIGHT_KEYS,
  'spheres[]': Object.keys(sphereShape),
  'spheres[].material': materialKeys,
  'spheres[].material.emission': Object.keys(emissionShape),
  'meshes[]': Object.keys(meshShape),
  'meshes[].material': materialKeys,
  'meshes[].material.emission': Object.keys(emissionShape),
  ...textureKnownKeys(['ground.material', 'spheres[].material', 'meshes[].material']),
};

/** The keys of a texture object (and its `uv`) at every material input that may be one. */
function textureKnownKeys(materials: readonly string[]): Record<string, readonly string[]> {
  const inputs = KINDS.flatMap((k) => [
    ...(k.textures ?? []).map((t) => [t.key, t.input] as const),
    ...(k.opacity ? [['opacity', 'scalar'] as const] : []),
    ...(k.normalMap ? [['normalMap', 'normal'] as const] : []),
    ...(k.texturedEmission ? [['emission.color', 'color'] as const] : []),
  ]);
  return Object.fromEntries(
    materials.flatMap((m) => inputs.flatMap(([key, input]) => [[`${m}.${key}`, TEXTURE_KEYS[input]], [`${m}.${key}.uv`, UV_KEYS]])),
  );
}

function distance(a: Vec3, b: Vec3): number {
  return Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

// ---------------------------------------------------------------- parsing

/** Validates and normalizes a scene (a parsed JSON value). Throws `SceneError` only. */
export function parseScene(input: unknown): Scene {
  const result = safeParseScene(input);
  if (!result.ok) throw new SceneError(result.issues);
  return result.scene;
}

/** Like `parseScene`, but returns the issues instead of throwing. Never throws. */
export function safeParseScene(input: unknown): SafeParseResult {
  try {
    const result = sceneSchema.safeParse(input, { error: messageFor });
    const versionProblems = versionIssues(input);
    if (result.success && versionProblems.length === 0) return { ok: true, scene: copyScene(result.data) };
    const issues = result.success ? [] : toSceneIssues(result.error.issues);
    const seen = new Set(issues.map((issue) => issue.path));
    return { ok: false, issues: [...versionProblems.filter((issue) => !seen.has(issue.path)), ...issues] };
  } catch (error) {
    // A last resort: inputs that are not plain JSON (throwing getters, proxies...).
    return { ok: false, issues: [{ path: '', message: `could not be read (${describe(error)})` }] };
  }
}

/**
 * Parses scene JSON text: checks its size (at most MAX_SCENE_BYTES bytes of
 * UTF-8), then the JSON syntax, then the scene. Throws `SceneError` only.
 */
export function parseSceneText(text: string): Scene {
  const result = safeParseSceneText(text);
  if (!result.ok) throw new SceneError(result.issues);
  return result.scene;
}

/** Like `parseSceneText`, but returns the issues instead of throwing. Never throws. */
export function safeParseSceneText(text: string): SafeParseResult {
  if (typeof text !== 'string') return failure('must be JSON text (a string)');
  const bytes = utf8Length(text, MAX_SCENE_BYTES + 1);
  if (bytes > MAX_SCENE_BYTES) {
    return failure(`must be at most ${MAX_SCENE_BYTES} bytes of UTF-8 text`);
  }
  let json: unknown;
  try {
    json = JSON.parse(text.charCodeAt(0) === 0xfeff ? text.slice(1) : text);
  } catch (error) {
    return failure(`invalid JSON: ${jsonErrorMessage(error, text)}`);
  }
  return safeParseScene(json);
}

function failure(message: string): SafeParseResult {
  return { ok: false, issues: [{ path: '', message }] };
}

/** UTF-8 length of `text` as TextEncoder would encode it, counting no further than `stop`. */
function utf8Length(text: string, stop: number): number {
  if (text.length >= stop) return text.length; // every UTF-16 unit takes at least one byte
  let bytes = 0;
  for (let i = 0; i < text.length && bytes < stop; i++) {
    const unit = text.charCodeAt(i);
    if (unit < 0x80) bytes += 1;
    else if (unit < 0x800) bytes += 2;
    else if (unit >= 0xd800 && unit < 0xdc00 && isLowSurrogate(text.charCodeAt(i + 1))) {
      bytes += 4;
      i++;
    } else bytes += 3; // the rest of the BMP, and lone surrogates (encoded as U+FFFD)
  }
  return bytes;
}

function isLowSurrogate(unit: number): boolean {
  return unit >= 0xdc00 && unit < 0xe000;
}

/** The engine's message, plus line and column when it only gives a position. */
function jsonErrorMessage(error: unknown, text: string): string {
  const message = describe(error);
  const position = /at position (\d+)/.exec(message);
  if (!position || /line/i.test(message)) return message;
  const before = text.slice(0, Number(position[1]));
  const line = before.split('\n').length;
  const column = before.length - before.lastIndexOf('\n');
  return `${message} (line ${line}, column ${column})`;
}

function describe(error: unknown): string {
  try {
    const message = error instanceof Error ? error.message : String(error);
    return message.length > 200 ? `${message.slice(0, 200)}...` : message;
  } catch {
    return 'unknown error';
  }
}

// ---------------------------------------------------------------- messages

type RawIssue = Parameters<z.core.$ZodErrorMap>[0];

/** Short human messages for zod's issue codes (schema-specific messages take precedence). */
function messageFor(issue: RawIssue): string {
  switch (issue.code) {
    case 'invalid_type':
      if (issue.input === undefined) return 'required';
      if (issue.expected === 'number') {
        return typeof issue.input === 'number' ? 'must be a finite number' : 'must be a number';
      }
      if (issue.expected === 'int') return 'must be an integer';
      if (issue.expected === 'array' || issue.expected === 'tuple') return 'must be an array';
      return `must be ${/^[aeiou]/.test(issue.expected) ? 'an' : 'a'} ${issue.expected}`;
    case 'too_small':
      if (issue.origin === 'array') return `must have at least ${issue.minimum} items`;
      return `must be ${issue.inclusive ? '>=' : '>'} ${formatNumber(Number(issue.minimum))}`;
    case 'too_big':
      if (issue.origin === 'int') return 'must be an integer';
      if (issue.origin === 'array') return `must have at most ${issue.maximum} items`;
      return `must be ${issue.inclusive ? '<=' : '<'} ${formatNumber(Number(issue.maximum))}`;
    case 'invalid_value':
      return `must be ${issue.values.map((value) => JSON.stringify(value)).join(' or ')}`;
    case 'unrecognized_keys':
      return 'unknown key';
    default:
      return 'is invalid';
  }
}

/** 1000000 -> "1e6"; small numbers as written. */
function formatNumber(value: number): string {
  return Math.abs(value) >= 1e5 ? value.toExponential().replace('e+', 'e') : String(value);
}

/** zod issues -> one SceneIssue per bad value (first message per path), capped. */
function toSceneIssues(issues: readonly z.core.$ZodIssue[]): SceneIssue[] {
  const result: SceneIssue[] = [];
  const seen = new Set<string>();
  let dropped = 0;
  // The message is made only for issues that are shown (typo suggestions cost time).
  const add = (path: string, message: () => string) => {
    if (seen.has(path)) return;
    seen.add(path);
    if (result.length < MAX_REPORTED_ISSUES) result.push({ path, message: message() });
    else dropped++;
  };
  for (const issue of issues) {
    if (issue.code === 'unrecognized_keys') {
      for (const key of issue.keys) add(formatPath([...issue.path, key]), () => unknownKeyMessage(issue.path, key));
    } else {
      add(formatPath(issue.path), () => issue.message);
    }
  }
  if (dropped > 0) result.push({ path: '', message: `${dropped} more problems not shown` });
  return result;
}

/** "unknown key", with a suggestion when the key looks like a typo of an allowed one. */
function unknownKeyMessage(objectPath: readonly PropertyKey[], key: string): string {
  const pattern = formatPath(objectPath.map((part) => (typeof part === 'number' ? -1 : part)));
  const known = KNOWN_KEYS[pattern] ?? [];
  // Keys of another material kind or environment kind (such as "ior" on a material without one).
  if (known.includes(key)) return 'unknown key for this type (see "type", or "map" for environments)';
  const wanted = simplify(key);
  if (wanted.length > 32) return 'unknown key';
  let best: string | undefined;
  let bestDistance = wanted.length <= 3 ? 2 : 3; // accept 1 edit in short keys, 2 in longer ones
  for (const candidate of known) {
    const d = editDistance(wanted, simplify(candidate));
    if (d < bestDistance) [best, bestDistance] = [candidate, d];
  }
  return best === undefined ? 'unknown key' : `unknown key (did you mean "${best}"?)`;
}

const simplify = (key: string) => key.toLowerCase().replace(/[\s_-]/g, '');

/** Edit distance counting insertions, deletions, substitutions and swaps of neighbours (for short strings). */
function editDistance(a: string, b: string): number {
  const d: number[][] = Array.from({ length: a.length + 1 }, (_, i) => [i]);
  for (let j = 1; j <= b.length; j++) d[0][j] = j;
  for (let i = 1; i <= a.length; i++) {
    for (let j = 1; j <= b.length; j++) {
      const cost = a[i - 1] === b[j - 1] ? 0 : 1;
      d[i][j] = Math.min(d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost);
      if (i > 1 && j > 1 && a[i - 1] === b[j - 2] && a[i - 2] === b[j - 1]) {
        d[i][j] = Math.min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[a.length][b.length];
}

const IDENTIFIER = /^[A-Za-z_$][\w$]*$/;
const MAX_KEY_CHARS = 40;

/**
 * ["spheres", 2, "material"] -> "spheres[2].material". Indices -1 print as
 * "[]"; keys that are not identifiers print quoted (`["my key"]`), and keys
 * longer than 40 characters are cut short with "...".
 */
export function formatPath(path: readonly PropertyKey[]): string {
  let text = '';
  for (const part of path) {
    if (typeof part === 'number') text += part < 0 ? '[]' : `[${part}]`;
    else {
      let key = String(part);
      if (key.length > MAX_KEY_CHARS) key = `${key.slice(0, MAX_KEY_CHARS)}...`;
      if (IDENTIFIER.test(key)) text += text === '' ? key : `.${key}`;
      else text += `[${JSON.stringify(key)}]`;
    }
  }
  return text;
}

// ---------------------------------------------------------------- output

type ParsedScene = z.output<typeof sceneSchema>;

/**
 * A fresh plain `Scene` with exactly the documented keys (-0 becomes 0). The
 * typed copies also check at compile time that the schema's output fits `Scene`.
 */
function copyScene(parsed: ParsedScene): Scene {
  return {
    version: parsed.version,
    camera: copyCamera(parsed.camera),
    image: { width: parsed.image.width, height: parsed.image.height },
    render: { maxBounces: parsed.render.maxBounces },
    environment: parsed.environment && copyEnvironment(parsed.environment),
    ground: parsed.ground && copyGround(parsed.ground),
    lights: parsed.lights.map(copyLight),
    spheres: parsed.spheres.map(copySphere),
    meshes: parsed.meshes.map((m) => copyMesh(m, parsed.version)),
  };
}

function copyCamera(c: Camera): Camera {
  const camera: Camera = {
    position: vec(c.position),
    target: vec(c.target),
    up: vec(c.up),
    fov: c.fov,
    aperture: num(c.aperture),
  };
  if (c.focusDistance !== undefined) camera.focusDistance = c.focusDistance;
  return camera;
}

const copyEnvironment = (e: Environment): Environment =>
  'map' in e
    ? { map: e.map, intensity: num(e.intensity), rotation: num(e.rotation) }
    : { color: vec(e.color), intensity: num(e.intensity) };
const copyGround = (g: Ground): Ground => ({ height: num(g.height), material: copyMaterial(g.material) });
const copyMaterial = (m: Material): Material => normalizeMaterial(m as unknown as Record<string, unknown>);
/** Without `material`, a version-3 mesh keeps its file's own materials (null); an older one has the default. */
const copyMesh = (m: z.output<z.ZodObject<typeof meshShape>>, version: number): Mesh => ({
  file: m.file,
  material: m.material ? copyMaterial(m.material) : version >= 3 ? null : defaultMaterial(),
  position: vec(m.position),
  rotation: vec(m.rotation),
  scale: typeof m.scale === 'number' ? [m.scale, m.scale, m.scale] : vec(m.scale),
});
const copyLight = (l: Light): Light => normalizeLight(l as unknown as Record<string, unknown>);
const copySphere = (s: Sphere): Sphere => ({ center: vec(s.center), radius: s.radius, material: copyMaterial(s.material) });
const vec = (v: Vec3): Vec3 => [num(v[0]), num(v[1]), num(v[2])];
const num = (x: number) => (x === 0 ? 0 : x);

