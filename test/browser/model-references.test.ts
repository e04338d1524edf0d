/**
 * Models as their authors made them (glTF materials) against their Mitsuba 3
 * references (4096 spp), with the noise-derived block test of
 * references.test.ts (test/support/referenceBlocks.ts), region by region:
 * each of the model's materials is the set of blocks that it covers (a CPU
 * ray cast through every pixel's centre), checked on its own, so a single
 * broken feature fails by its name.
 *
 * - gltf-materials: panels.glb, one primitive per feature (a texture
 *   transform with a metallic-roughness texture, an emissive texture with
 *   KHR_materials_emissive_strength, an alpha-masked cut-out, a
 *   normal-mapped panel, a clear-coated ball).
 * - bench: a real CC0 model (512x1024 textures, a normal map, no tangents).
 *   The reference uses Mitsuba's normalmap frame, whose bitangent turns
 *   over on the mirrored charts (5% of its area); there the format's frame
 *   (glTF's) is the truth, so blocks that a mirrored chart covers are not
 *   judged by the reference (they are counted and reported).
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { predictedRelMse, relativeMse, type LinearImage } from '../../src/node/imageMetrics';
import { loadSceneAssets } from '../../src/scene/assets';
import { cameraRay } from '../../src/scene/camera';
import { resolveFileMaterials } from '../../src/scene/fileMaterials';
import { transformMesh } from '../../src/scene/mesh';
import type { Scene, TriangleMesh } from '../../src/scene/types';
import { FIXTURES, loadFixtureScene, loadReference, renderLinear, useRenderSession } from '../support/browser';
import { blockStats, summarize, writeFailureImages } from '../support/referenceBlocks';

const Z_MAX = 6;
const BATCHES = 8;
/** A block belongs to a region when at least this share of its pixel centres see it. */
const REGION_SHARE = 0.5;

interface ModelCase {
  spp: number;
  block: number;
  /** The worst-block bound in a material's region (its blocks' sigma must be under a third of it). */
  worstBlock: number;
  /** The same over the whole image, where a few blocks (the ground beside the light) are noisier. */
  wholeWorstBlock: number;
  /** Names of the model's materials by their index in the file (for messages). */
  labels: Record<number, string>;
}

/**
 * Sized like references.test.ts: the largest block sigma at most a third of
 * the worst-block bound. 16x16 blocks (the panels are about 30 pixels wide:
 * a 32x32 block would mix two features). Measured 2026-12-02 at 128 spp on
 * gltf-materials: every region's block sigma at most 1.13% (bound 5%), the
 * whole image's 3.14% (the ground beside the light: bound 10%).
 */
const MODELS: Record<string, ModelCase> = {
  'gltf-materials': {
    spp: 128,
    block: 16,
    worstBlock: 0.05,
    wholeWorstBlock: 0.1,
    labels: { 0: 'texture transform and metallic-roughness texture', 1: 'emissive texture with emissive strength', 2: 'alpha-masked cut-out', 3: 'normal-mapped panel', 4: 'clear-coated ball' },
  },
  // At 128 spp its block sigma was at most 1.00% (2026-12-02): 96 keeps it near 1.15%.
  bench: { spp: 96, block: 16, worstBlock: 0.05, wholeWorstBlock: 0.1, labels: { 0: 'benchMat (textures and normal map)' } },
};

describe('models against their Mitsuba 3 references, region by region', () => {
  const session = useRenderSession();

  for (const [name, model] of Object.entries(MODELS)) {
    it(`${name} at ${model.spp} spp: every material's region matches its reference within the measured noise`, async () => {
      const scene = loadFixtureScene(name);
      const reference = loadReference(name);
      const regions = await materialRegions(scene, model.block);
      const batches: LinearImage[] = [];
      for (let seed = 1; seed <= BATCHES; seed++) batches.push(await renderLinear(session(), scene, model.spp / BATCHES, seed));
      const stats = blockStats(scene, batches, reference, model.block, 4096);
      const judged = new Set(Array.from({ length: stats.cols * stats.rows }, (_, b) => b).filter((b) => !regions.mirrored.has(b)));
      const reports: string[] = [];
      const failures: string[] = [];
      const check = (label: string, blocks: Iterable<number>, bound = model.worstBlock) => {
        const s = summarize(stats, [...blocks].filter((b) => judged.has(b)));
        const report = `${name} / ${label}: ${s.blocks} blocks, worst ${(s.worstError * 100).toFixed(2)}% (${s.worstZ.toFixed(2)} sigma at ${s.worstZBlock}), largest sigma ${(s.worstSigma * 100).toFixed(2)}%`;
        reports.push(report);
        if (s.worstZ >= Z_MAX || s.worstError >= bound || s.worstSigma >= bound / 3) failures.push(report);
        return s;
      };
      for (const [k, blocks] of regions.byMaterial) {
        const s = check(model.labels[k] ?? `material ${k}`, blocks);
        expect(s.blocks, `${name}: material ${k} covers no block to judge`).toBeGreaterThan(0);
      }
      check('the whole image', judged, model.wholeWorstBlock);
      const relMse = relativeMse(stats.image, reference);
      const predicted = predictedRelMse(stats.variance, reference);
      const mirrored = summarize(stats, regions.mirrored);
      reports.push(
        `${name}: relMSE ${relMse.toExponential(3)} (noise predicts ${predicted.toExponential(3)}); ${regions.mirrored.size} blocks on mirrored charts not judged ` +
          `(there: worst ${(mirrored.worstError * 100).toFixed(2)}%, ${mirrored.worstZ.toFixed(2)} sigma)`,
      );
      console.log(reports.join('\n'));
      if (failures.length > 0) writeFailureImages(name, stats.image, reference);
      expect(failures, failures.join('\n')).toEqual([]);
      expect(regions.mirrored.size, 'mirrored charts cover a few blocks at most').toBeLessThanOrEqual(Math.ceil(0.15 * stats.cols * stats.rows));
      // relMSE over the whole image includes the mirrored charts' blocks: bounded only where there are none.
      if (regions.mirrored.size === 0) expect(relMse).toBeLessThan(1.5 * predicted + 1e-4);
    }, 900_000);
  }
});

/**
 * Which blocks each of the model's materials covers (by the file's material
 * index), and the blocks where a mirrored chart (texture coordinates turned
 * over against the triangle's winding, unlike most of the model) covers at
 * least one pixel centre.
 */
async function materialRegions(scene: Scene, block: number): Promise<{ byMaterial: Map<number, Set<number>>; mirrored: Set<number> }> {
  const folder = new URL('scenes/', FIXTURES);
  const assets = await loadSceneAssets(scene, async (file) => new Uint8Array(readFileSync(new URL(file, folder))));
  const resolved = resolveFileMaterials(scene, assets);
  const meshes = resolved.scene.meshes.map((mesh) => ({
    material: Number(/#material(\d+)$/.exec(mesh.file)?.[1] ?? -1),
    world: transformMesh(resolved.assets.meshes.get(mesh.file)!, mesh),
  }));
  const { width, height } = scene.image;
  const cols = Math.floor(width / block);
  const rows = Math.floor(height / block);
  const counts = new Map<number, Uint32Array>();
  const mirroredBlocks = new Set<number>();
  const majority = majorityOrientation(meshes.map((m) => m.world));
  for (let y = 0; y < rows * block; y++) {
    for (let x = 0; x < cols * block; x++) {
      const ray = cameraRay(scene.camera, width / height, (x + 0.5) / width, (y + 0.5) / height);
      const hit = closestTriangle(meshes.map((m) => m.world), ray.origin, ray.direction);
      if (!hit) continue;
      const b = Math.floor(y / block) * cols + Math.floor(x / block);
      const k = meshes[hit.mesh].material;
      if (!counts.has(k)) counts.set(k, new Uint32Array(cols * rows));
      counts.get(k)![b]++;
      if (uvOrientation(meshes[hit.mesh].world, hit.triangle) === -majority) mirroredBlocks.add(b);
    }
  }
  const byMaterial = new Map<number, Set<number>>();
  for (const [k, perBlock] of counts) {
    byMaterial.set(k, new Set([...perBlock.keys()].filter((b) => perBlock[b] >= REGION_SHARE * block * block)));
  }
  return { byMaterial, mirrored: mirroredBlocks };
}

/** The closest triangle along a ray (Moller-Trumbore over every triangle: the models are small). */
function closestTriangle(meshes: TriangleMesh[], o: number[], d: number[]): { mesh: number; triangle: number } | null {
  let best = Infinity;
  let found: { mesh: number; triangle: number } | null = null;
  meshes.forEach((mesh, m) => {
    const { positions: p, indices } = mesh;
    for (let t = 0; t < indices.length / 3; t++) {
      const [a, b, c] = [indices[3 * t] * 3, indices[3 * t + 1] * 3, indices[3 * t + 2] * 3];
      const e1 = [p[b] - p[a], p[b + 1] - p[a + 1], p[b + 2] - p[a + 2]];
      const e2 = [p[c] - p[a], p[c + 1] - p[a + 1], p[c + 2] - p[a + 2]];
      const q = cross(d, e2);
      const det = dot(e1, q);
      if (Math.abs(det) < 1e-12) continue;
      const s = [o[0] - p[a], o[1] - p[a + 1], o[2] - p[a + 2]];
      const u = dot(s, q) / det;
      if (u < 0 || u > 1) continue;
      const r = cross(s, e1);
      const v = dot(d, r) / det;
      if (v < 0 || u + v > 1) continue;
      const dist = dot(e2, r) / det;
      if (dist > 1e-6 && dist < best) {
        best = dist;
        found = { mesh: m, triangle: t };
      }
    }
  });
  return found;
}

/** +1 or -1: whether the triangle's texture coordinates wind the same way as its vertices (0 without coordinates). */
function uvOrientation(mesh: TriangleMesh, t: number): number {
  if (!mesh.uvs) return 0;
  const uv = (c: number) => [mesh.uvs![mesh.indices[3 * t + c] * 2], mesh.uvs![mesh.indices[3 * t + c] * 2 + 1]];
  const [a, b, c] = [uv(0), uv(1), uv(2)];
  return Math.sign((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
}

/** The uv winding most of the models' area has. */
function majorityOrientation(meshes: TriangleMesh[]): number {
  let sum = 0;
  for (const mesh of meshes) for (let t = 0; t < mesh.indices.length / 3; t++) sum += uvOrientation(mesh, t);
  return sum >= 0 ? 1 : -1;
}

const cross = (a: number[], b: number[]) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const dot = (a: number[], b: number[]) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];

