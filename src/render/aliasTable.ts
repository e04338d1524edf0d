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
  if (n === 0 || weights.every((w) => w === weights[0])) return { pdf, threshold: new Array<number>(n).fill(1), alias: pdf.map((_, i) => i) };
  const builder = new AliasBuilder(n);
  builder.build(pdf);
  return { pdf, threshold: Array.from(builder.threshold), alias: Array.from(builder.alias) };
}

/**
 * Vose's construction on arrays kept from table to table (the emitter-choice
 * grid builds thousands of tables on every edit of a light:
 * render/lightChoice.ts), for `n` entries.
 */
export class AliasBuilder {
  readonly threshold: Float64Array;
  readonly alias: Int32Array;
  private readonly scaled: Float64Array;
  private readonly small: Int32Array;
  private readonly large: Int32Array;

  constructor(private readonly n: number) {
    this.threshold = new Float64Array(n);
    this.alias = new Int32Array(n);
    this.scaled = new Float64Array(n);
    this.small = new Int32Array(n);
    this.large = new Int32Array(n);
  }

  /** The thresholds and aliases of probabilities `pdf` (summing to 1) into `threshold` and `alias`. */
  build(pdf: ArrayLike<number>): void {
    const { n, threshold, alias, scaled, small, large } = this;
    let ns = 0;
    let nl = 0;
    for (let i = 0; i < n; i++) {
      threshold[i] = 1;
      alias[i] = i;
      scaled[i] = pdf[i] * n;
      if (scaled[i] < 1) small[ns++] = i;
      else large[nl++] = i;
    }
    while (ns > 0 && nl > 0) {
      const s = small[--ns];
      const l = large[nl - 1];
      threshold[s] = scaled[s];
      alias[s] = l;
      scaled[l] -= 1 - scaled[s];
      if (scaled[l] < 1) small[ns++] = large[--nl];
    }
    // What is left keeps itself: its threshold is 1 up to rounding.
  }
}
