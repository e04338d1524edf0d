/**
 * Walker's alias table (Vose's construction): draws index i with probability
 * weights[i] / sum in constant time from one uniform number u:
 *   i = floor(u * n), keep i if frac(u * n) < threshold[i], else alias[i].
 * Equal weights give thresholds of exactly 1 (every index keeps itself), so
 * the draw is then the plain uniform choice floor(u * n).
 */
export interface AliasTable {
  pdf: number[];
  threshold: number[];
  alias: number[];
}

export function buildAliasTable(weights: readonly number[]): AliasTable {
  const n = weights.length;
  const total = weights.reduce((sum, w) => sum + w, 0);
  const pdf = weights.map((w) => w / total);
  const threshold = new Array<number>(n).fill(1);
  const alias = weights.map((_, i) => i);
  if (n === 0 || weights.every((w) => w === weights[0])) return { pdf, threshold, alias };
  const scaled = pdf.map((p) => p * n);
  const small = scaled.flatMap((s, i) => (s < 1 ? [i] : []));
  const large = scaled.flatMap((s, i) => (s >= 1 ? [i] : []));
  while (small.length > 0 && large.length > 0) {
    const s = small.pop()!;
    const l = large[large.length - 1];
    threshold[s] = scaled[s];
    alias[s] = l;
    scaled[l] -= 1 - scaled[s];
    if (scaled[l] < 1) small.push(large.pop()!);
  }
  // What is left is 1 up to rounding.
  for (const i of [...small, ...large]) threshold[i] = 1;
  return { pdf, threshold, alias };
}
