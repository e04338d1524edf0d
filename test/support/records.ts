/** Record `index` of a table starting at texel `first`, read back into its named fields (tests of the packed layout). */
export function readRecord(
  data: Float32Array,
  first: number,
  layout: { texels: number; fields: { name: string; type: string; texel: number; offset: number }[] },
  index: number,
): Record<string, number | number[]> {
  const base = (first + index * layout.texels) * 4;
  const out: Record<string, number | number[]> = {};
  for (const f of layout.fields) {
    const at = base + f.texel * 4 + f.offset;
    out[f.name] = f.type === 'vec3' ? Array.from(data.subarray(at, at + 3)) : data[at];
  }
  return out;
}
