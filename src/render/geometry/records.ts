/**
 * Records derived from the prepared geometry (pure: no GL), uploaded by
 * src/render/passes/assetTextures.ts: the instance table and the
 * emissive-triangle table.
 */
import { inverseAffine } from '../../scene/mesh';
import { buildAliasTable } from '../aliasTable';
import { BVH_TEXTURE_WIDTH } from '../bvh';
import { INSTANCE } from '../layout/scene';
import { packRecord } from '../layout/records';
import type { MeshEmitterSlots } from '../packScene';
import { triangleArea, type WorldMeshes } from './world';

/**
 * The instance table (InstanceRecord, layout/scene.ts): the world group
 * first when it is stored (identity, its triangles' own meshes), then
 * every mesh of each shared group with its matrices and mesh index.
 */
export function instanceRecords(world: WorldMeshes, roots: readonly number[]): Float32Array {
  const { groups } = world;
  const identity = new Float64Array([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]);
  const entries: { toWorld: Float64Array; root: number; mesh: number }[] = [];
  if (groups.world.length > 0) entries.push({ toWorld: identity, root: roots[0], mesh: -1 });
  const firstShared = groups.world.length > 0 ? 1 : 0;
  groups.shared.forEach((users, g) => {
    for (const i of users) entries.push({ toWorld: world.toWorld[i], root: roots[firstShared + g], mesh: i });
  });
  const out = new Float32Array(entries.length * INSTANCE.texels * 4);
  entries.forEach((e, k) => out.set(packRecord(INSTANCE, { ...matrixRows(e.toWorld), root: e.root, mesh: e.mesh }), k * INSTANCE.texels * 4));
  return out;
}

/** The rows (3x4) of an affine column-major matrix and of its inverse, as InstanceRecord fields. */
function matrixRows(m: Float64Array): Record<string, number[]> {
  const row = (a: ArrayLike<number>, r: number) => [a[r], a[4 + r], a[8 + r], a[12 + r]];
  const inv = inverseAffine(m);
  return {
    toObjectX: row(inv, 0), toObjectY: row(inv, 1), toObjectZ: row(inv, 2),
    toWorldX: row(m, 0), toWorldY: row(m, 1), toWorldZ: row(m, 2),
  };
}

/**
 * The emissive triangles for lights/mesh_emitter.glsl, BVH_TEXTURE_WIDTH
 * texels a row: slot `first + k` of a mesh's range holds (BVH index of its
 * triangle k, alias threshold, BVH index of the alias triangle, 0) of a
 * per-mesh alias table that picks triangles in proportion to their area.
 */
export function emissiveTriangleRecords(world: WorldMeshes, triangleOrder: Uint32Array, emitters: readonly MeshEmitterSlots[]): Float32Array {
    const bvhIndex = new Uint32Array(triangleOrder.length);
    triangleOrder.forEach((input, j) => (bvhIndex[input] = j));
    // Emissive meshes are in the world group, the first: its inputs are its meshes' triangles in order.
    const firstInput: number[] = [];
    world.groups.world.reduce((sum, i) => ((firstInput[i] = sum), sum + world.sizes[i].triangles), 0);
    const slots = emitters.reduce((n, e) => Math.max(n, e.first + e.count), 0);
    const width = BVH_TEXTURE_WIDTH;
    const data = new Float32Array(width * Math.max(1, Math.ceil(slots / width)) * 4);
    for (const e of emitters) {
      const mesh = world.meshes[e.mesh]!;
      const areas = Array.from({ length: e.count }, (_, t) => triangleArea(mesh.positions, mesh.indices, t));
      const table = buildAliasTable(areas);
      for (let k = 0; k < e.count; k++) {
        const o = (e.first + k) * 4;
        data[o] = bvhIndex[firstInput[e.mesh] + k];
        data[o + 1] = table.threshold[k];
        data[o + 2] = bvhIndex[firstInput[e.mesh] + table.alias[k]];
      }
    }
  return data;
}
