/**
 * Wavefront MTL text to principled materials (scene format "Meshes in
 * version 3": `Kd`, `map_Kd`, `Pr`/`map_Pr`, `Pm`/`map_Pm`, `Ke`/`map_Ke`,
 * `map_Bump`/`bump`/`norm`, `d`/`map_d`/`Tr`, `Ni`). Pure: the caller reads
 * the file. Each material is built as the JSON `{"type": "principled", ...}`
 * and parsed by the principled schema, so it is exactly what a scene giving
 * those keys would get (every default filled, -0 cleaned).
 *
 * Choices (the format leaves them open):
 * - A map replaces its constant (`map_Kd` replaces `Kd`, `map_Pr` replaces
 *   `Pr`...): the texture's scale is 1, as Blender's importer links the
 *   image in place of the value.
 * - Colors are taken as linear numbers (the format's colors are linear),
 *   clamped to [0, 1] (`Ke` to [0, 1e12]: emission may exceed 1).
 * - `Ni` is the index of refraction, the same quantity as `ior` (it sets the
 *   specular Fresnel term of the principled BSDF), clamped to 4. `Ni` at or
 *   below 1 is ignored with a warning: exporters write `Ni 1` as "no
 *   refraction", which as an ior would remove every specular highlight.
 * - `map_Bump`/`bump` are read as tangent-space normal maps (what exporters
 *   such as Blender's write there); `norm` wins where both are given. `-bm`
 *   is the normal map's scale.
 * - `map_d` reads channel "a" when it names the `map_Kd` image (an image
 *   with alpha, Blender's convention) and "r" otherwise (a grey mask);
 *   `-imfchan` overrides it for every scalar map.
 * - `-o` and `-s` are the uv transform `uv' = o + s uv` (three.js's MTL
 *   loader: offset and repeat) in the file's coordinates, where v counts up
 *   from the bottom. The mesh's coordinates are turned over (`w = 1 - v`),
 *   so in them the transform is `w' = (1 - s_v - o_v) + s_v w` (see uvOf).
 * - Texture names are paths relative to the MTL's folder; they are returned
 *   relative to the OBJ's folder (the MTL's own path joined in front),
 *   with `\` read as `/`.
 * Everything else (the Phong keys Ka, Ks, Ns, illum..., map options such as
 * -clamp or -mm) is ignored and listed once in the warnings.
 */
import { materialSchema, normalizeMaterial, type PrincipledMaterial } from '../../materials/registry';
import { MAX_IOR, MIN_IOR } from '../../materials/kind';
import { MAX_INTENSITY } from '../schemaParts';

export interface MtlFile {
  /** By `newmtl` name; a name defined twice keeps its last definition. */
  materials: Map<string, PrincipledMaterial>;
  /** One line each, starting with the MTL's path. */
  warnings: string[];
}

type Rgb = [number, number, number];
type ScalarChannel = 'r' | 'g' | 'b' | 'a';

/** A map statement: its image (relative to the OBJ's folder) and the options that matter. */
interface MapRef {
  image: string;
  offset: [number, number];
  scale: [number, number];
  bumpScale?: number;
  channel?: ScalarChannel;
}

/** What one `newmtl` block said, before defaults. */
interface MtlEntry {
  kd?: Rgb;
  mapKd?: MapRef;
  pr?: number;
  mapPr?: MapRef;
  pm?: number;
  mapPm?: MapRef;
  ke?: Rgb;
  mapKe?: MapRef;
  bump?: MapRef;
  norm?: MapRef;
  d?: number;
  tr?: number;
  mapD?: MapRef;
  ni?: number;
}

const MAP_KEYS: Record<string, keyof MtlEntry> = {
  map_kd: 'mapKd',
  map_pr: 'mapPr',
  map_pm: 'mapPm',
  map_ke: 'mapKe',
  map_bump: 'bump',
  bump: 'bump',
  norm: 'norm',
  map_d: 'mapD',
};
const COLOR_KEYS: Record<string, 'kd' | 'ke'> = { kd: 'kd', ke: 'ke' };
const NUMBER_KEYS: Record<string, 'pr' | 'pm' | 'd' | 'tr' | 'ni'> = { pr: 'pr', pm: 'pm', d: 'd', tr: 'tr', ni: 'ni' };
/** Map options and how many values follow them (a range: -o, -s and -t take 1 to 3 numbers). */
const MAP_OPTIONS: Record<string, [number, number]> = {
  '-o': [1, 3], '-s': [1, 3], '-t': [1, 3], '-bm': [1, 1], '-boost': [1, 1], '-mm': [2, 2], '-texres': [1, 1],
  '-clamp': [1, 1], '-blendu': [1, 1], '-blendv': [1, 1], '-cc': [1, 1], '-imfchan': [1, 1], '-type': [1, 1],
};
/** `-imfchan` values a scalar map can read (m: the matte channel, alpha; l: luminance, r of a grey image). */
const IMF_CHANNELS: Record<string, ScalarChannel> = { r: 'r', g: 'g', b: 'b', m: 'a', l: 'r' };

/**
 * The MTL statements this loader does not read, by lower-case keyword: an
 * ignored statement is named in the warning only if it is one of these (a
 * file that is not an MTL must not have its words repeated).
 */
const KNOWN_IGNORED = new Set([
  'ka', 'ks', 'ns', 'illum', 'tf', 'sharpness', 'map_ka', 'map_ks', 'map_ns', 'map_aat', 'disp', 'decal', 'refl',
  'ps', 'pc', 'pcr', 'aniso', 'anisor', 'map_ps', 'map_pc', 'map_pcr', 'map_aniso', 'map_anisor',
]);

/** The default principled material: the schema's defaults. */
export function defaultPrincipled(): PrincipledMaterial {
  return normalizeMaterial(materialSchema('principled')!.parse({ type: 'principled' }) as Record<string, unknown>) as PrincipledMaterial;
}

/** Parses MTL `text`; `mtlPath` is the MTL's path relative to the OBJ's folder (as `mtllib` gives it). */
export function parseMtl(text: string, mtlPath: string): MtlFile {
  const entries = new Map<string, MtlEntry>();
  const ignored = new Set<string>();
  let unknown = 0;
  const notes: string[] = [];
  const folder = folderOf(mtlPath.replace(/\\/g, '/'));
  let current: MtlEntry | null = null;
  const lines = text.split(/\r?\n/);
  for (let n = 0; n < lines.length; n++) {
    const line = lines[n].trim();
    if (line === '' || line[0] === '#') continue;
    const fields = line.split(/\s+/);
    const keyword = fields[0].toLowerCase();
    const where = `line ${n + 1}`;
    if (keyword === 'newmtl') {
      current = {};
      entries.set(fields.slice(1).join(' '), current);
    } else if (!current) {
      notes.push(`${where}: "${fields[0]}" before any newmtl is ignored`);
    } else if (keyword in COLOR_KEYS) {
      const rgb = parseRgb(fields.slice(1));
      if (rgb) current[COLOR_KEYS[keyword]] = rgb;
      else notes.push(`${where}: "${fields[0]}" needs 1 or 3 numbers (spectral and xyz colors are not read): ignored`);
    } else if (keyword in NUMBER_KEYS) {
      const value = Number(fields[1]);
      if (fields.length >= 2 && Number.isFinite(value)) current[NUMBER_KEYS[keyword]] = value;
      else notes.push(`${where}: "${fields[0]}" needs a number: ignored`);
    } else if (keyword in MAP_KEYS) {
      const map = parseMap(fields.slice(1), folder, MAP_KEYS[keyword], (message) => notes.push(`${where}: ${fields[0]} ${message}`));
      if (map) (current as Record<string, MapRef>)[MAP_KEYS[keyword]] = map;
    } else if (KNOWN_IGNORED.has(keyword)) {
      ignored.add(fields[0]);
    } else {
      unknown++;
    }
  }
  const materials = new Map<string, PrincipledMaterial>();
  for (const [name, entry] of entries) materials.set(name, buildMaterial(entry, (message) => notes.push(`material "${name}": ${message}`)));
  const warnings = notes.map((note) => `${mtlPath}: ${note}`);
  if (ignored.size > 0) warnings.push(`${mtlPath}: ignored (no principled equivalent): ${[...ignored].join(', ')}`);
  if (unknown > 0) warnings.push(`${mtlPath}: ${unknown} line(s) with statements MTL does not define: ignored`);
  return { materials, warnings };
}

/** `r [g b]` (g and b default to r), each finite; null otherwise. */
function parseRgb(values: string[]): Rgb | null {
  if (values.length !== 1 && values.length !== 3) return null;
  const numbers = values.map(Number);
  if (!numbers.every(Number.isFinite)) return null;
  return (numbers.length === 1 ? [numbers[0], numbers[0], numbers[0]] : numbers) as Rgb;
}

/** `[options] file`: the options this loader uses, the others reported through `note`; null without a file name. */
function parseMap(args: string[], folder: string, key: keyof MtlEntry, note: (message: string) => void): MapRef | null {
  const map: MapRef = { image: '', offset: [0, 0], scale: [1, 1] };
  let i = 0;
  while (i < args.length && args[i].startsWith('-') && args[i].length > 1) {
    const option = args[i].toLowerCase();
    const range = MAP_OPTIONS[option];
    if (!range) {
      note(`option ${args[i]} is unknown: ignored`);
      i++;
      continue;
    }
    const values = optionValues(args, i + 1, range);
    i += 1 + values.length;
    if (values.length < range[0]) note(`option ${option} needs ${range[0]} value(s): ignored`);
    else applyOption(map, option, values, key, note);
  }
  const name = args.slice(i).join(' ');
  if (name === '') {
    note('names no image: ignored');
    return null;
  }
  map.image = joinPath(folder, name);
  return map;
}

/** The values after an option at `start`: up to `max`, numbers only for the options whose count varies. */
function optionValues(args: string[], start: number, [min, max]: [number, number]): string[] {
  const values: string[] = [];
  // Keep at least one argument for the file name.
  while (values.length < max && start + values.length < args.length - 1) {
    const value = args[start + values.length];
    if (values.length >= min && !Number.isFinite(Number(value))) break;
    values.push(value);
  }
  return values;
}

/** The maps read as one channel (the others read RGB). */
const SCALAR_MAPS: readonly (keyof MtlEntry)[] = ['mapPr', 'mapPm', 'mapD'];

function applyOption(map: MapRef, option: string, values: string[], key: keyof MtlEntry, note: (message: string) => void): void {
  const numbers = values.map(Number);
  const finite = numbers.every(Number.isFinite);
  const normal = key === 'bump' || key === 'norm';
  if (option === '-o' || option === '-s' || (option === '-bm' && normal)) {
    if (!finite) return note(`option ${option} needs numbers: ignored`);
    if (option === '-o') map.offset = [numbers[0], numbers[1] ?? 0];
    else if (option === '-s') map.scale = [numbers[0], numbers[1] ?? 1];
    else map.bumpScale = numbers[0];
  } else if (option === '-imfchan' && SCALAR_MAPS.includes(key) && IMF_CHANNELS[values[0].toLowerCase()]) {
    map.channel = IMF_CHANNELS[values[0].toLowerCase()];
  } else {
    note(`option ${option} ${values.join(' ')} is ignored`);
  }
}

/** The principled material of one block, through the scene schema; the default material if the schema refuses it. */
function buildMaterial(entry: MtlEntry, note: (message: string) => void): PrincipledMaterial {
  const parsed = materialSchema('principled')!.safeParse(principledJson(entry, note));
  if (parsed.success) return normalizeMaterial(parsed.data as Record<string, unknown>) as PrincipledMaterial;
  const issue = parsed.error.issues[0];
  note(`${issue.path.join('.')}: ${issue.message}: the default material`);
  return defaultPrincipled();
}

function principledJson(entry: MtlEntry, note: (message: string) => void): Record<string, unknown> {
  const json: Record<string, unknown> = { type: 'principled' };
  if (entry.mapKd) json.baseColor = { image: entry.mapKd.image, uv: uvOf(entry.mapKd) };
  else if (entry.kd) json.baseColor = entry.kd.map((c) => clamp(c, 0, 1));
  setScalar(json, 'roughness', entry.pr, entry.mapPr, 'r');
  setScalar(json, 'metallic', entry.pm, entry.mapPm, 'r');
  const alphaChannel = entry.mapD && entry.mapKd && entry.mapD.image === entry.mapKd.image ? 'a' : 'r';
  setScalar(json, 'opacity', entry.d ?? (entry.tr === undefined ? undefined : 1 - entry.tr), entry.mapD, alphaChannel);
  const normal = entry.norm ?? entry.bump;
  if (normal) json.normalMap = { image: normal.image, scale: normal.bumpScale ?? 1, uv: uvOf(normal) };
  if (entry.mapKe) json.emission = { color: { image: entry.mapKe.image, uv: uvOf(entry.mapKe) }, intensity: 1 };
  else if (entry.ke && entry.ke.some((c) => c > 0)) json.emission = { color: entry.ke.map((c) => clamp(c, 0, MAX_INTENSITY)), intensity: 1 };
  if (entry.ni !== undefined && entry.ni <= 1) note(`Ni ${entry.ni} (no refraction) is ignored: ior stays the default`);
  else if (entry.ni !== undefined) json.ior = clamp(entry.ni, MIN_IOR, MAX_IOR);
  return json;
}

/** A scalar key: the map (one channel, scale 1) where there is one, else the number clamped to [0, 1]. */
function setScalar(json: Record<string, unknown>, key: string, value: number | undefined, map: MapRef | undefined, channel: ScalarChannel): void {
  if (map) json[key] = { image: map.image, channel: map.channel ?? channel, uv: uvOf(map) };
  else if (value !== undefined) json[key] = clamp(value, 0, 1);
}

/**
 * `-o` and `-s` in the mesh's turned-over coordinates. The file looks up
 * `V = o_v + s_v v` with v up from the bottom; the mesh holds `w = 1 - v`
 * and images count rows down from the top, so the lookup there is
 * `1 - V = (1 - s_v - o_v) + s_v w`. u is not turned over.
 */
export function uvOf(map: { offset: [number, number]; scale: [number, number] }): { offset: [number, number]; scale: [number, number]; rotation: number } {
  const [ou, ov] = map.offset;
  const [su, sv] = map.scale;
  return { offset: [ou, 1 - sv - ov], scale: [su, sv], rotation: 0 };
}

const clamp = (x: number, lo: number, hi: number) => Math.min(hi, Math.max(lo, x));

/** The folder part of a `/`-separated path ('' for a bare name). */
const folderOf = (path: string) => path.slice(0, path.lastIndexOf('/') + 1);

/** `folder` + `name` with `\` as `/`, `.` and `x/..` segments removed; an absolute name is kept as it is. */
export function joinPath(folder: string, name: string): string {
  const slashed = name.replace(/\\/g, '/');
  if (slashed.startsWith('/') || /^[A-Za-z]:\//.test(slashed)) return slashed;
  const out: string[] = [];
  for (const part of `${folder}${slashed}`.split('/')) {
    if (part === '' || part === '.') continue;
    if (part === '..' && out.length > 0 && out[out.length - 1] !== '..') out.pop();
    else out.push(part);
  }
  return out.join('/');
}
