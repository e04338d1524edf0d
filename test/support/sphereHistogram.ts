/**
 * Histograms over the whole sphere of directions, uniform in (cos theta,
 * phi) so that every bin has the same solid angle, for chi-square tests of
 * the shader's samplers against their pdfs.
 */

export interface SphereBins {
  cosBins: number;
  phiBins: number;
}

export function sphereBin(x: number, y: number, z: number, { cosBins, phiBins }: SphereBins): number {
  const u = Math.min(cosBins - 1, Math.max(0, Math.floor(((z + 1) / 2) * cosBins)));
  const v = Math.min(phiBins - 1, Math.floor((((Math.atan2(y, x) + 2 * Math.PI) % (2 * Math.PI)) / (2 * Math.PI)) * phiBins));
  return u * phiBins + v;
}

/**
 * Expected counts of `n` samples: the pdf (channel `channel` of a kernel's
 * grid of sub x sub points per bin, at cell centres uniform in cos theta and
 * phi) integrated over each bin by the midpoint rule; `mass` is the pdf's
 * integral over the sphere.
 */
export function expectedCounts(
  grid: Float32Array,
  channel: number,
  bins: SphereBins,
  sub: number,
  n: number,
): { expected: Float64Array; mass: number } {
  const { cosBins, phiBins } = bins;
  const cell = (2 / (cosBins * sub)) * ((2 * Math.PI) / (phiBins * sub));
  const expected = new Float64Array(cosBins * phiBins);
  let mass = 0;
  for (let gy = 0; gy < cosBins * sub; gy++) {
    for (let gx = 0; gx < phiBins * sub; gx++) {
      const p = grid[(gy * phiBins * sub + gx) * 4 + channel] * cell;
      expected[Math.floor(gy / sub) * phiBins + Math.floor(gx / sub)] += p * n;
      mass += p;
    }
  }
  return { expected, mass };
}

/** Direction of grid cell (gx, gy), as the kernels' gridDirection computes it. */
export function gridDirection(gx: number, gy: number, width: number, height: number): [number, number, number] {
  const cosTheta = (2 * (gy + 0.5)) / height - 1;
  const sinTheta = Math.sqrt(Math.max(0, 1 - cosTheta * cosTheta));
  const phi = (2 * Math.PI * (gx + 0.5)) / width;
  return [sinTheta * Math.cos(phi), sinTheta * Math.sin(phi), cosTheta];
}
