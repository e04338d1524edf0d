/**
 * glTF vertex colors (scene format "glTF materials": baseColor =
 * baseColorFactor x baseColorTexture x COLOR_0) from the decoded file to
 * the renderer's inputs: a mesh wearing its file's materials carries the
 * flag and its colors go into the BVH; a scene's own material on the same
 * file uses none; the shader switch is on only then (the default scene
 * compiles no vertex-color code). The render itself: test/browser/vertex-colors.test.ts.
 */
import { describe, expect, it } from 'vitest';
import { buildBvh } from '../../src/render/bvh/build';
import { packBvhGroups, triangleTexel } from '../../src/render/bvh/pack';
import { colorTexel, hitColor } from '../../src/render/bvh/traverse';
import { groupMeshes, trianglesIn } from '../../src/render/bvh/groups';
import { bvhInputs, groupInputs, prepareWorldMeshes } from '../../src/render/geometry/world';
import { packScene } from '../../src/render/packScene';
import { featureDefines } from '../../src/render/shaderChunks';
import { loadSceneAssets } from '../../src/scene/assets';
import { resolveFileMaterials } from '../../src/scene/fileMaterials';
import { defaultScene } from '../../src/scene/presets';
import { parseScene } from '../../src/scene/schema';
import type { Scene } from '../../src/scene/types';
import { colorQuadGlb } from '../support/colorQuad';

const sceneWith = (meshes: unknown[]): Scene =>
  parseScene({ version: 3, camera: { position: [0, 0, 3], target: [0, 0, 0] }, environment: { color: [1, 1, 1], intensity: 1 }, meshes });

async function loaded(scene: Scene, colors = true) {
  const bytes = await colorQuadGlb({ colors, baseColorFactor: [1, 1, 1] });
  return loadSceneAssets(scene, async () => bytes);
}

describe('vertex colors', () => {
  it('a mesh wearing its file material with COLOR_0 multiplies by its colors; the same file under a scene material does not', async () => {
    const scene = sceneWith([{ file: 'quad.glb' }, { file: 'quad.glb', position: [3, 0, 0], material: { type: 'principled' } }]);
    const assets = await loaded(scene);
    const resolved = resolveFileMaterials(scene, assets);
    expect(resolved.scene.meshes.map((m) => m.vertexColors)).toEqual([true, false]);
    const world = prepareWorldMeshes(resolved.scene, resolved.assets);
    expect(world.vertexColors).toEqual([true, false]);
    const packed = packScene(resolved.scene, { meshes: world.sizes, groups: world.groups });
    expect(packed.features.vertexColors).toBe(true);
    expect(featureDefines(packed.features).HAS_VERTEX_COLORS).toBe(1);

    // Only the first mesh's triangles carry colors in the BVH: red at x = -1, green at x = +1 (its corners').
    const groups = bvhInputs(scene, assets);
    expect(groups.flat().map((m) => !!m.colors)).toEqual([true, false]);
    const bvh = packBvhGroups(groups.map((meshes) => ({ bvh: buildBvh(meshes), meshes })));
    for (let j = 0; j < bvh.triangleCount; j++) {
      const mesh = bvh.texture.data[triangleTexel(j) * 4 + 11];
      expect(colorTexel(bvh.texture.data, j) >= 0).toBe(mesh === 0);
      if (mesh !== 0) continue;
      const input = groups[0][0];
      const id = bvh.triangleOrder[j];
      for (const [c, [b1, b2]] of [[0, 0], [1, 0], [0, 1]].entries()) {
        const v = input.indices[id * 3 + c];
        const x = input.positions[v * 3];
        expect(hitColor(bvh, { triangle: j, t: 1, b1, b2 })).toEqual(x < 0 ? [1, 0, 0] : [0, 1, 0]);
      }
    }
  });

  it('no COLOR_0, or no meshes wearing file materials: the switch is off', async () => {
    for (const [scene, colors] of [[sceneWith([{ file: 'quad.glb' }]), false], [sceneWith([{ file: 'quad.glb', material: { type: 'principled' } }]), true]] as const) {
      const assets = await loaded(scene, colors);
      const resolved = resolveFileMaterials(scene, assets);
      const world = prepareWorldMeshes(resolved.scene, resolved.assets);
      const packed = packScene(resolved.scene, { meshes: world.sizes, groups: world.groups });
      expect(packed.features.vertexColors).toBe(false);
      expect(featureDefines(packed.features).HAS_VERTEX_COLORS).toBe(0);
      expect(bvhInputs(scene, assets).flat().every((m) => !m.colors)).toBe(true);
    }
  });

  it('an instanced file stores its colors once, in object space, when its meshes multiply by them', async () => {
    const scene = sceneWith([{ file: 'quad.glb' }, { file: 'quad.glb', position: [3, 0, 0], scale: [2, 2, 2] }]);
    const { scene: resolved, assets } = resolveFileMaterials(scene, await loaded(scene));
    // Instanced whatever the size (the threshold lowered to 0).
    const groups = groupMeshes(resolved, trianglesIn(assets), 0);
    expect(groups).toEqual({ world: [], shared: [[0, 1]] });
    const data = (i: number) => assets.meshes.get(resolved.meshes[i].file)!;
    const vertexColors = resolved.meshes.map((m) => m.vertexColors);
    const [[shared]] = groupInputs(groups, () => {
      throw new Error('an instanced mesh is not copied');
    }, data, vertexColors);
    expect(shared.colors).toBe(data(0).colors);
    expect(shared.mesh).toBe(-1);
    const [[plain]] = groupInputs(groups, () => data(0), data, [false, false]);
    expect(plain.colors).toBeNull();
  });

  it('the default scene compiles no vertex-color code', () => {
    const packed = packScene(defaultScene());
    expect(featureDefines(packed.features).HAS_VERTEX_COLORS).toBe(0);
  });
});
