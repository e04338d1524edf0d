/**
 * Time to compute MikkTSpace tangent frames (src/scene/mesh/tangents.ts) in
 * Node: the bunny of node_modules/bunny (the small one: 3,674 triangles;
 * smooth area-weighted normals and a spherical projection for uvs, since the
 * package has neither) and bumpy spheres (bench/meshGen.ts, smooth, uvs from
 * latitude and longitude) of 70,000 triangles (the Stanford bunny's size)
 * and 1,000,000. Prints the median of the runs, and how much of it is the
 * WebAssembly itself.
 *
 *   npx tsx bench/tangents.ts [--runs 3]
 */
import { createRequire } from 'node:module';
import { loadMikkTSpace } from '../src/scene/mesh/mikktspace';
import { meshTangents } from '../src/scene/mesh/tangents';
import type { TriangleMesh } from '../src/scene/types';
import { bumpySphere } from './meshGen';

const runsArg = process.argv.indexOf('--runs');
const RUNS = runsArg > 0 ? Number(process.argv[runsArg + 1]) : 3;

function bunny(): TriangleMesh {
  const { positions, cells } = createRequire(import.meta.url)('bunny') as { positions: number[][]; cells: number[][] };
  const mesh: TriangleMesh = { positions: Float32Array.from(positions.flat()), normals: null, indices: Uint32Array.from(cells.flat()) };
  return withSphericalUvs({ ...mesh, normals: smoothNormals(mesh) });
}

/** Area-weighted vertex normals (the sum of the triangles' unnormalized cross products), normalized. */
function smoothNormals(mesh: TriangleMesh): Float32Array {
  const p = mesh.positions;
  const sum = new Float64Array(p.length);
  for (let t = 0; t < mesh.indices.length; t += 3) {
    const [a, b, c] = [mesh.indices[t] * 3, mesh.indices[t + 1] * 3, mesh.indices[t + 2] * 3];
    const e1 = [p[b] - p[a], p[b + 1] - p[a + 1], p[b + 2] - p[a + 2]];
    const e2 = [p[c] - p[a], p[c + 1] - p[a + 1], p[c + 2] - p[a + 2]];
    const n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
    for (const v of [a, b, c]) for (let k = 0; k < 3; k++) sum[v + k] += n[k];
  }
  const out = new Float32Array(p.length);
  for (let v = 0; v < p.length; v += 3) {
    const length = Math.hypot(sum[v], sum[v + 1], sum[v + 2]) || 1;
    for (let k = 0; k < 3; k++) out[v + k] = sum[v + k] / length;
  }
  return out;
}

/** u = longitude / 2 pi, v = colatitude / pi about the bounding box's centre. */
function withSphericalUvs(mesh: TriangleMesh): TriangleMesh {
  const p = mesh.positions;
  const centre = [0, 1, 2].map((k) => {
    let [lo, hi] = [Infinity, -Infinity];
    for (let i = k; i < p.length; i += 3) [lo, hi] = [Math.min(lo, p[i]), Math.max(hi, p[i])];
    return (lo + hi) / 2;
  });
  const uvs = new Float32Array((p.length / 3) * 2);
  for (let v = 0; v < p.length / 3; v++) {
    const [x, y, z] = [0, 1, 2].map((k) => p[v * 3 + k] - centre[k]);
    uvs[v * 2] = (Math.atan2(-z, x) / (2 * Math.PI) + 1) % 1;
    uvs[v * 2 + 1] = Math.acos(Math.max(-1, Math.min(1, y / (Math.hypot(x, y, z) || 1)))) / Math.PI;
  }
  return { ...mesh, uvs };
}

const median = (values: number[]) => values.slice().sort((a, b) => a - b)[Math.floor(values.length / 2)];

async function time(name: string, mesh: TriangleMesh): Promise<void> {
  const generate = await loadMikkTSpace();
  const timed = async () => {
    const start = performance.now();
    await meshTangents(mesh);
    return (performance.now() - start) / 1000;
  };
  await timed(); // compiles the WebAssembly, warms the JIT
  const totals: number[] = [];
  for (let r = 0; r < RUNS; r++) totals.push(await timed());
  // The WebAssembly alone, on the same de-indexed arrays.
  const corners = mesh.indices.length;
  const [positions, normals, uvs] = [new Float32Array(corners * 3), new Float32Array(corners * 3), new Float32Array(corners * 2)];
  for (let c = 0; c < corners; c++) {
    const v = mesh.indices[c];
    positions.set(mesh.positions.subarray(v * 3, v * 3 + 3), c * 3);
    normals.set(mesh.normals!.subarray(v * 3, v * 3 + 3), c * 3);
    uvs.set(mesh.uvs!.subarray(v * 2, v * 2 + 2), c * 2);
  }
  const wasmSeconds: number[] = [];
  for (let r = 0; r < RUNS; r++) {
    const start = performance.now();
    generate(positions, normals, uvs);
    wasmSeconds.push((performance.now() - start) / 1000);
  }
  console.log(`${name}: ${(corners / 3).toLocaleString('en')} triangles, meshTangents ${median(totals).toFixed(3)} s (median of ${RUNS}), of which MikkTSpace's WebAssembly ${median(wasmSeconds).toFixed(3)} s`);
}

await time('bunny', bunny());
await time('bumpy sphere', withSphericalUvs(bumpySphere(70_000)));
await time('bumpy sphere', withSphericalUvs(bumpySphere(1_000_000)));
