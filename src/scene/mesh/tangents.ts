/**
 * Tangent frames for normal maps (scene format, "Meshes in version 3"):
 * glTF's rule. A frame is (x, y, z, w): x the tangent, along increasing u;
 * the bitangent cross(normal, x) * w points up the image, toward decreasing
 * v (v = 0 is the image's top row). The file's own frame (glTF TANGENT,
 * `TriangleMesh.tangents`) is used where it gives one; elsewhere MikkTSpace
 * computes it, the reference algorithm (the `mikktspace` package: the
 * gltf-rs port of Mikkelsen's C code, compiled to WebAssembly).
 *
 * Never computed on load: it costs about 10 us a triangle, linear in the
 * count, so the renderer asks only for the meshes whose material has a
 * normal map. `npx tsx bench/tangents.ts` (Node 20, one thread, on the
 * shared 2-core machine at load average ~5): node_modules/bunny (3,674
 * triangles) 0.03 s, a 70,000-triangle smooth sphere (the Stanford bunny's
 * size) 0.45 s, 1,000,000 triangles 11.9 s, 90% of it inside the
 * WebAssembly (the de-indexing and checks here: ~1 s); a flat 980,000-triangle
 * grid at load ~2.7: 9.8 s in the WebAssembly alone.
 *
 * The WebAssembly cannot compile on the page's main thread (its
 * Content-Security-Policy has no 'wasm-unsafe-eval'): call this from a
 * worker there (Node and workers are fine).
 */
import type { TriangleMesh } from '../types';
import { loadMikkTSpace, type GenerateTangents } from './mikktspace';
import { triangleCross } from './finalize';

/**
 * The tangent frame at every triangle corner of `mesh`, for its normal map:
 * 4 floats (x, y, z, w) per entry of `mesh.indices` (corner k of triangle t
 * at `(3 t + k) * 4`), in the mesh's space (object space for a decoded file,
 * world space for a transformMesh copy). Per corner, not per vertex, because
 * MikkTSpace may give one vertex different frames in different triangles
 * (a seam between mirrored charts shares its uvs; w differs).
 *
 * - x is a unit vector orthogonal to the corner's shading normal (its
 *   vertex normal, or the face normal where the mesh is flat or the normal
 *   is zero) within float rounding; w is +1 or -1; bitangent =
 *   cross(n, x) * w points toward decreasing v.
 * - A vertex's given tangent (`mesh.tangents`, w != 0) is returned as given
 *   (unit, w = +-1, but only as orthogonal to the normal as the file made it).
 * - Corners whose frame MikkTSpace cannot define (every triangle around them
 *   has zero uv area) get an arbitrary unit x orthogonal to n and w = 1, never NaN.
 * - null when the mesh has no texture coordinates (no normal map can be looked up).
 * - `texCoord` 1: MikkTSpace on `uvs1` instead (a glTF normalTexture with
 *   `texCoord: 1`; a file's TANGENT is used as given either way).
 *
 * The shader must still make the interpolated x orthogonal to the
 * interpolated normal (Gram-Schmidt) before use.
 */
export async function meshTangents(mesh: TriangleMesh, texCoord: 0 | 1 = 0): Promise<Float32Array | null> {
  const uvs = (texCoord === 1 ? mesh.uvs1 : mesh.uvs) ?? null;
  if (!uvs) return null;
  const given = mesh.tangents ?? null;
  const out = given && everyCornerGiven(mesh.indices, given) ? new Float32Array(mesh.indices.length * 4) : mikkTSpaceCorners(mesh, uvs, await loadMikkTSpace());
  if (given) overlayGiven(mesh.indices, given, out);
  return out;
}

function everyCornerGiven(indices: Uint32Array, tangents: Float32Array): boolean {
  for (let c = 0; c < indices.length; c++) if (tangents[indices[c] * 4 + 3] === 0) return false;
  return true;
}

/** The given tangents (per vertex) over `out` (per corner), where a vertex has one. */
function overlayGiven(indices: Uint32Array, tangents: Float32Array, out: Float32Array): void {
  for (let c = 0; c < indices.length; c++) {
    const v = indices[c] * 4;
    if (tangents[v + 3] !== 0) out.set(tangents.subarray(v, v + 4), c * 4);
  }
}

/** MikkTSpace over the de-indexed triangles (it needs them unwelded; it welds identical corners itself). */
function mikkTSpaceCorners(mesh: TriangleMesh, uv: Float32Array, generate: GenerateTangents): Float32Array {
  if (mesh.indices.length === 0) return new Float32Array(0); // MikkTSpace fails on no triangles
  const { positions, normals, uvs } = cornerAttributes(mesh, uv);
  let tangents: Float32Array;
  try {
    tangents = generate(positions, normals, uvs);
  } catch (error) {
    // "Failed to generate tangents." where the C code returns false (out of memory).
    throw new Error(`MikkTSpace failed on ${mesh.indices.length / 3} triangles: ${(error as Error)?.message ?? String(error)}`);
  }
  if (tangents.length !== mesh.indices.length * 4) throw new Error(`MikkTSpace returned ${tangents.length / 4} tangents for ${mesh.indices.length} triangle corners`);
  for (let c = 0; c < mesh.indices.length; c++) {
    // Run on this format's v-down coordinates, MikkTSpace's cross(n, x) * w points toward increasing v.
    tangents[c * 4 + 3] = -tangents[c * 4 + 3];
    if (!isFrame(tangents, normals, c)) fallbackFrame(tangents, normals, c);
  }
  return tangents;
}

/** Positions, shading normals and uvs per corner (3, 3 and 2 floats). */
function cornerAttributes(mesh: TriangleMesh, uv: Float32Array): { positions: Float32Array; normals: Float32Array; uvs: Float32Array } {
  const { indices, positions: p, normals: n } = mesh;
  const positions = new Float32Array(indices.length * 3);
  const normals = new Float32Array(indices.length * 3);
  const uvs = new Float32Array(indices.length * 2);
  const face = [0, 0, 0];
  for (let t = 0; t < indices.length; t += 3) {
    faceNormal(p, indices[t], indices[t + 1], indices[t + 2], face);
    for (let c = t; c < t + 3; c++) {
      const v = indices[c];
      positions.set(p.subarray(v * 3, v * 3 + 3), c * 3);
      uvs[c * 2] = uv[v * 2];
      uvs[c * 2 + 1] = uv[v * 2 + 1];
      const smooth = n !== null && (n[v * 3] !== 0 || n[v * 3 + 1] !== 0 || n[v * 3 + 2] !== 0);
      if (smooth) normals.set(n.subarray(v * 3, v * 3 + 3), c * 3);
      else normals.set(face, c * 3);
    }
  }
  return { positions, normals, uvs };
}

/** The unit normal of triangle (a, b, c) by its winding; zero for a zero-area triangle. */
function faceNormal(p: Float32Array, a: number, b: number, c: number, out: number[]): void {
  const [x, y, z] = triangleCross(p, a, b, c);
  const length = Math.hypot(x, y, z);
  const k = length > 0 ? 1 / length : 0;
  out[0] = x * k;
  out[1] = y * k;
  out[2] = z * k;
}

/** A finite unit x orthogonal to the corner's normal, and w = +-1. */
function isFrame(t: Float32Array, n: Float32Array, c: number): boolean {
  const [x, y, z, w] = [t[c * 4], t[c * 4 + 1], t[c * 4 + 2], t[c * 4 + 3]];
  const length = Math.hypot(x, y, z);
  const dot = x * n[c * 3] + y * n[c * 3 + 1] + z * n[c * 3 + 2];
  return Math.abs(length - 1) < 1e-3 && Math.abs(dot) < 1e-3 && (w === 1 || w === -1); // false for NaN
}

/** Any unit x orthogonal to n (Duff et al.'s branchless basis; +x for a zero n), w = 1. */
function fallbackFrame(t: Float32Array, n: Float32Array, c: number): void {
  const [nx, ny, nz] = [n[c * 3], n[c * 3 + 1], n[c * 3 + 2]];
  let x = [1, 0, 0];
  if (nx !== 0 || ny !== 0 || nz !== 0) {
    const sign = nz >= 0 ? 1 : -1;
    const a = -1 / (sign + nz);
    x = [1 + sign * nx * nx * a, sign * nx * ny * a, -sign * nx];
  }
  t.set([x[0], x[1], x[2], 1], c * 4);
}
