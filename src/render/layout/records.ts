/**
 * Packed records, each defined once: the field table below generates the
 * TypeScript packer (`packRecord`), the GLSL `#define`s of every field's
 * texel, and the GLSL struct and loader of each record (`recordGlsl`). A
 * record is a run of RGBA32F texels; fields are laid out in the order given,
 * a vec3 never straddling two texels. Integers are stored as exact floats.
 *
 * The layout is plain flat float arrays, so the same data could back WebGPU
 * storage buffers.
 */
export type FieldType = 'float' | 'int' | 'vec3' | 'vec4';

export interface Field {
  name: string;
  type: FieldType;
  texel: number;
  /** Component within the texel (0 = x). */
  offset: number;
}

export interface RecordLayout {
  /** GLSL struct name (also the prefix of the defines, upper-cased). */
  name: string;
  texels: number;
  fields: Field[];
}

const SIZE: Record<FieldType, number> = { float: 1, int: 1, vec3: 3, vec4: 4 };
const SWIZZLE = 'xyzw';

/** Lays out `fields` in order, starting a new texel where one would not fit. */
export function defineRecord(name: string, fields: [string, FieldType][]): RecordLayout {
  const laid: Field[] = [];
  let texel = 0;
  let offset = 0;
  for (const [field, type] of fields) {
    if (offset + SIZE[type] > 4) [texel, offset] = [texel + 1, 0];
    laid.push({ name: field, type, texel, offset });
    offset += SIZE[type];
  }
  return { name, texels: texel + 1, fields: laid };
}

export type RecordValues = Record<string, number | readonly number[]>;

/** The record's texels as 4 * texels floats; fields not given stay 0. */
export function packRecord(layout: RecordLayout, values: RecordValues): Float32Array {
  const out = new Float32Array(layout.texels * 4);
  for (const [name, value] of Object.entries(values)) {
    const field = layout.fields.find((f) => f.name === name);
    if (!field) throw new Error(`${layout.name} has no field ${name}`);
    const items = typeof value === 'number' ? [value] : value;
    if (items.length !== SIZE[field.type]) throw new Error(`${layout.name}.${name}: expected ${SIZE[field.type]} values`);
    out.set(items, field.texel * 4 + field.offset);
  }
  return out;
}

const upper = (name: string) => name.replace(/([a-z])([A-Z])/g, '$1_$2').toUpperCase();

/** `<RECORD>_TEXELS` and `<RECORD>_<FIELD>_TEXEL` for the hot loops that fetch one texel. */
export function recordDefines(layout: RecordLayout): Record<string, number> {
  const prefix = upper(layout.name);
  const defines: Record<string, number> = { [`${prefix}_TEXELS`]: layout.texels };
  for (const field of layout.fields) defines[`${prefix}_${upper(field.name)}_TEXEL`] = field.texel;
  return defines;
}

/** The GLSL expression of a field read from texels named `<texels>t0`, `<texels>t1`, ... */
export function fieldRead(field: Field, texels = ''): string {
  const size = SIZE[field.type];
  const swizzle = SWIZZLE.slice(field.offset, field.offset + size);
  const read = `${texels}t${field.texel}.${swizzle}`;
  return field.type === 'int' ? `int(${read})` : read;
}

/**
 * The GLSL struct of a record and `<Name> read<Name>(int first)`, which
 * reads the record whose first texel is `first` through `fetch(int)`.
 */
export function recordGlsl(layout: RecordLayout, fetch: string): string {
  const members = layout.fields.map((f) => `  ${f.type} ${f.name};`).join('\n');
  const texels = Array.from({ length: layout.texels }, (_, t) => `  vec4 t${t} = ${fetch}(first + ${t});`).join('\n');
  const assigns = layout.fields.map((f) => `  r.${f.name} = ${fieldRead(f)};`).join('\n');
  return [
    `struct ${layout.name} {\n${members}\n};`,
    `${layout.name} read${layout.name}(int first) {\n${texels}\n  ${layout.name} r;\n${assigns}\n  return r;\n}`,
  ].join('\n');
}
