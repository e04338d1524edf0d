/**
 * A TypeScript reference of the GGX lobe's directional albedo, for the glossy
 * furnace: E(mu) = integral of f * cos over the hemisphere for a white GGX
 * conductor with separable Smith G = the mean of G1(wi) over visible normals
 * (Heitz 2018), computed here by deterministic quadrature.
 */

function g1(v: number[], alpha: number): number {
  const a2 = alpha * alpha;
  return (2 * v[2]) / (v[2] + Math.sqrt(a2 * (v[0] * v[0] + v[1] * v[1]) + v[2] * v[2]));
}

function visibleNormal(wo: number[], alpha: number, u1: number, u2: number): number[] {
  const vh = normalize([alpha * wo[0], alpha * wo[1], wo[2]]);
  const lenSq = vh[0] * vh[0] + vh[1] * vh[1];
  const t1 = lenSq > 0 ? [-vh[1] / Math.sqrt(lenSq), vh[0] / Math.sqrt(lenSq), 0] : [1, 0, 0];
  const t2 = [vh[1] * t1[2] - vh[2] * t1[1], vh[2] * t1[0] - vh[0] * t1[2], vh[0] * t1[1] - vh[1] * t1[0]];
  const r = Math.sqrt(u1);
  const phi = 2 * Math.PI * u2;
  const p1 = r * Math.cos(phi);
  const s = 0.5 * (1 + vh[2]);
  const p2 = (1 - s) * Math.sqrt(Math.max(0, 1 - p1 * p1)) + s * r * Math.sin(phi);
  const p3 = Math.sqrt(Math.max(0, 1 - p1 * p1 - p2 * p2));
  const nh = [0, 1, 2].map((i) => p1 * t1[i] + p2 * t2[i] + p3 * vh[i]);
  return normalize([alpha * nh[0], alpha * nh[1], Math.max(1e-7, nh[2])]);
}

function normalize(v: number[]): number[] {
  const l = Math.hypot(v[0], v[1], v[2]);
  return v.map((x) => x / l);
}

/** Directional albedo of the white GGX lobe at cos(theta_o) = mu. */
export function ggxAlbedo(mu: number, alpha: number, grid = 160): number {
  const wo = [Math.sqrt(Math.max(0, 1 - mu * mu)), 0, mu];
  let sum = 0;
  for (let i = 0; i < grid; i++) {
    for (let j = 0; j < grid; j++) {
      const h = visibleNormal(wo, alpha, (i + 0.5) / grid, (j + 0.5) / grid);
      const d = wo[0] * h[0] + wo[1] * h[1] + wo[2] * h[2];
      const wi = [2 * d * h[0] - wo[0], 2 * d * h[1] - wo[1], 2 * d * h[2] - wo[2]];
      if (wi[2] > 0) sum += g1(wi, alpha);
    }
  }
  return sum / (grid * grid);
}
