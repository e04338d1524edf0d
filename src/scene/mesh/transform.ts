/**
 * Object to world for meshes, as the scene format defines it (Mitsuba's
 * `to_world`): `translate(position) * Rz * Ry * Rx * scale`, angles in
 * degrees about the world axes (right-hand rule). Points go through the
 * matrix, normals through its inverse transpose (then renormalized).
 * Matrices are column-major 4x4 (glTF and WebGL order).
 */
import type { TriangleMesh } from '../types';

export type Mat4 = ArrayLike<number>;
export type Vec3 = readonly [number, number, number];

export interface MeshTransform {
  position?: Vec3;
  /** Degrees about x, then y, then z (world axes). */
  rotation?: Vec3;
  /** A number or per-axis factors, every one > 0. */
  scale?: number | Vec3;
}

/** Column-major `T * Rz * Ry * Rx * S`. */
export function meshToWorldMatrix(transform: MeshTransform): Float64Array {
  const [px, py, pz] = transform.position ?? [0, 0, 0];
  const [ax, ay, az] = (transform.rotation ?? [0, 0, 0]).map((d) => (d * Math.PI) / 180);
  const s = transform.scale ?? 1;
  const [sx, sy, sz] = typeof s === 'number' ? [s, s, s] : s;
  const [cx, cy, cz, snx, sny, snz] = [Math.cos(ax), Math.cos(ay), Math.cos(az), Math.sin(ax), Math.sin(ay), Math.sin(az)];
  // R = Rz * Ry * Rx, row-major entries r[row][col].
  const r = [
    [cz * cy, cz * sny * snx - snz * cx, cz * sny * cx + snz * snx],
    [snz * cy, snz * sny * snx + cz * cx, snz * sny * cx - cz * snx],
    [-sny, cy * snx, cy * cx],
  ];
  const scale = [sx, sy, sz];
  const m = new Float64Array(16);
  for (let col = 0; col < 3; col++) {
    for (let row = 0; row < 3; row++) m[col * 4 + row] = r[row][col] * scale[col];
  }
  m[12] = px;
  m[13] = py;
  m[14] = pz;
  m[15] = 1;
  return m;
}

export interface TransformedVertices {
  positions: Float64Array;
  normals: Float64Array | null;
  /** The matrix mirrors (negative determinant): triangle winding must be flipped to keep faces outward. */
  mirrored: boolean;
}

/** The cofactor matrix of the upper 3x3 of `m` (column-major 3x3: det * its inverse transpose) and its determinant. */
function cofactors(m: Mat4): { c: number[]; det: number } {
  const c = [
    m[5] * m[10] - m[9] * m[6], m[8] * m[6] - m[4] * m[10], m[4] * m[9] - m[8] * m[5],
    m[9] * m[2] - m[1] * m[10], m[0] * m[10] - m[8] * m[2], m[8] * m[1] - m[0] * m[9],
    m[1] * m[6] - m[5] * m[2], m[4] * m[2] - m[0] * m[6], m[0] * m[5] - m[4] * m[1],
  ];
  return { c, det: m[0] * c[0] + m[4] * c[3] + m[8] * c[6] };
}

/** The inverse of an affine column-major 4x4 (world to object for a mesh's to_world). */
export function inverseAffine(m: Mat4): Float64Array {
  const { c, det } = cofactors(m);
  // A^-1 = transpose(cofactors) / det: row r, column k of the inverse is cofactor (k, r) = c[r * 3 + k].
  const inv = new Float64Array(16);
  for (let r = 0; r < 3; r++) for (let k = 0; k < 3; k++) inv[k * 4 + r] = c[r * 3 + k] / det;
  for (let r = 0; r < 3; r++) inv[12 + r] = -(inv[r] * m[12] + inv[4 + r] * m[13] + inv[8 + r] * m[14]);
  inv[15] = 1;
  return inv;
}

/** Points by `m`, normals by the inverse transpose of its upper 3x3, renormalized (a zero normal stays zero). */
export function applyMatrix(m: Mat4, positions: ArrayLike<number>, normals: ArrayLike<number> | null): TransformedVertices {
  const count = Math.floor(positions.length / 3);
  const outP = new Float64Array(count * 3);
  for (let i = 0; i < count; i++) {
    const x = positions[i * 3];
    const y = positions[i * 3 + 1];
    const z = positions[i * 3 + 2];
    outP[i * 3] = m[0] * x + m[4] * y + m[8] * z + m[12];
    outP[i * 3 + 1] = m[1] * x + m[5] * y + m[9] * z + m[13];
    outP[i * 3 + 2] = m[2] * x + m[6] * y + m[10] * z + m[14];
  }
  // Cofactor matrix = det * inverse transpose: the same directions, no division.
  const { c, det } = cofactors(m);
  const sign = det < 0 ? -1 : 1;
  let outN: Float64Array | null = null;
  if (normals) {
    outN = new Float64Array(count * 3);
    for (let i = 0; i < count; i++) {
      const x = normals[i * 3];
      const y = normals[i * 3 + 1];
      const z = normals[i * 3 + 2];
      // Row k of the cofactor matrix dotted with n gives component k.
      const nx = c[0] * x + c[3] * y + c[6] * z;
      const ny = c[1] * x + c[4] * y + c[7] * z;
      const nz = c[2] * x + c[5] * y + c[8] * z;
      const length = Math.hypot(nx, ny, nz);
      const k = length > 0 ? sign / length : 0;
      outN[i * 3] = nx * k;
      outN[i * 3 + 1] = ny * k;
      outN[i * 3 + 2] = nz * k;
    }
  }
  return { positions: outP, normals: outN, mirrored: det < 0 };
}

/**
 * Tangents (x, y, z, w per vertex, bitangent = cross(n, xyz) * w) by `m`:
 * xyz is a direction along the surface (dp/du), so it goes through the
 * upper 3x3 itself, renormalized. A mirroring `m` turns cross(n', t') over
 * relative to the transformed bitangent m * b, since cross(m t, m b) =
 * det(m) m^-T cross(t, b): w takes det's sign, so that the bitangent still
 * points up the image (toward decreasing v) on the transformed surface.
 * A (0, 0, 0, 0) tangent (none given) stays so.
 */
export function applyMatrixToTangents(m: Mat4, tangents: ArrayLike<number>): Float64Array {
  const count = Math.floor(tangents.length / 4);
  const out = new Float64Array(count * 4);
  const sign = cofactors(m).det < 0 ? -1 : 1;
  for (let i = 0; i < count; i++) {
    const x = tangents[i * 4];
    const y = tangents[i * 4 + 1];
    const z = tangents[i * 4 + 2];
    const tx = m[0] * x + m[4] * y + m[8] * z;
    const ty = m[1] * x + m[5] * y + m[9] * z;
    const tz = m[2] * x + m[6] * y + m[10] * z;
    const length = Math.hypot(tx, ty, tz);
    const k = length > 0 ? 1 / length : 0;
    out[i * 4] = tx * k;
    out[i * 4 + 1] = ty * k;
    out[i * 4 + 2] = tz * k;
    out[i * 4 + 3] = length > 0 ? tangents[i * 4 + 3] * sign : 0;
  }
  return out;
}

/** A world-space copy of `mesh` (object to world per the scene format), tangents included; texture coordinates are kept as they are (shared, not copied). */
export function transformMesh(mesh: TriangleMesh, transform: MeshTransform): TriangleMesh {
  const m = meshToWorldMatrix(transform);
  const world = applyMatrix(m, mesh.positions, mesh.normals);
  let indices = mesh.indices;
  if (world.mirrored) {
    indices = mesh.indices.slice();
    for (let t = 0; t < indices.length; t += 3) [indices[t + 1], indices[t + 2]] = [indices[t + 2], indices[t + 1]];
  }
  const tangents = mesh.tangents ? Float32Array.from(applyMatrixToTangents(m, mesh.tangents)) : null;
  return { positions: Float32Array.from(world.positions), normals: world.normals ? Float32Array.from(world.normals) : null, indices, uvs: mesh.uvs ?? null, uvs1: mesh.uvs1 ?? null, tangents };
}
