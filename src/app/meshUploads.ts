/**
 * Scene uploads that never freeze the page on a large mesh. The renderer
 * rebuilds the BVH on the calling thread whenever a mesh's data, transform or
 * grouping changes (src/render/passes/assetTextures.ts; materials, spheres,
 * lights and the ground never rebuild it); the page
 * instead builds it in the
 * BVH worker (buildBvhAsync) and uploads the scene when it is ready, handing
 * the renderer the result (setScene's `bvh`). Until then the image keeps showing the
 * scene as last uploaded; edits made meanwhile are coalesced: when a build
 * finishes, the latest scene is uploaded (or built for, if its meshes moved
 * again). Scenes without meshes upload at once.
 */
import { groupMeshes, trianglesIn } from '../render/bvh/groups';
import { buildBvhAsync } from '../render/bvh/buildAsync';
import { bvhInputs, prebuiltBvh, type PrebuiltBvh } from '../render/geometry/world';
import type { PathTracer } from '../render/PathTracer';
import type { SceneAssets } from '../scene/assets';
import type { Scene, TriangleMesh } from '../scene/types';

/**
 * Total triangles above which the BVH is built in the worker: every mesh.
 * Measured in Node on this (shared, loaded) machine: 180-360 ms for the
 * 3674-triangle bunny, 14 s for 1M triangles (bench/bvh-build.ts, removed
 * after 4bf13d0), so even the bunny would stall a drag if built on the
 * page's thread.
 */
export const ASYNC_BUILD_TRIANGLES = 0;

const dataIds = new WeakMap<TriangleMesh, number>();
let nextDataId = 1;
const dataId = (data: TriangleMesh | undefined) => {
  if (!data) return 0;
  let id = dataIds.get(data);
  if (id === undefined) dataIds.set(data, (id = nextDataId++));
  return id;
};

interface MeshState {
  /**
   * Everything the BVH depends on: data identity, grouping, the copied
   * meshes' transforms (an instance's move needs no new BVH; nor does a
   * material, which the mesh records give).
   */
  key: string;
  triangles: number;
}

function meshState(scene: Scene, assets: SceneAssets): MeshState {
  const data = scene.meshes.map((m) => assets.meshes.get(m.file));
  const groups = groupMeshes(scene, trianglesIn(assets));
  const copies = groups.world.map((i) => [scene.meshes[i].position, scene.meshes[i].rotation, scene.meshes[i].scale]);
  const key = JSON.stringify([data.map(dataId), groups, copies]);
  const triangles = data.reduce((sum, d) => sum + (d ? d.indices.length / 3 : 0), 0);
  return { key, triangles };
}

export class MeshUploads {
  private uploadedKey: string;
  private building: string | null = null;
  /** The BVH built in the worker for the meshes of state `key`, not yet uploaded. */
  private built: { key: string; bvh: PrebuiltBvh } | null = null;
  /** Milliseconds of the last worker build, for the page's statistics and tests. */
  lastBuildMs = 0;

  constructor(
    private readonly tracer: PathTracer,
    private readonly current: () => { scene: Scene; assets: SceneAssets },
    private readonly onError: (message: string) => void,
  ) {
    // The tracer starts without meshes (App); the first upload builds theirs.
    this.uploadedKey = meshState({ ...current().scene, meshes: [] }, current().assets).key;
  }

  /** True while a BVH is being built in the worker (the image shows the scene before the edit). */
  get pending(): boolean {
    return this.building !== null;
  }

  /** Uploads the current scene now, or once its BVH is built in the worker. */
  upload(): void {
    const { scene, assets } = this.current();
    const state = meshState(scene, assets);
    if (state.key === this.uploadedKey || state.key === this.built?.key || state.triangles <= ASYNC_BUILD_TRIANGLES) {
      const bvh = state.key === this.built?.key ? this.built.bvh : undefined;
      this.uploadedKey = state.key;
      this.built = null;
      // A copy: the tracer re-uploads its scene on a resize, and the page's
      // scene may by then hold edits whose BVH is still being built.
      this.tracer.setScene(structuredClone(scene), assets, { bvh });
      showState(this.building ? 'building' : 'ready');
      return;
    }
    // One build at a time: when it finishes, upload() runs again for the latest scene.
    if (this.building !== null) return;
    this.build(structuredClone(scene), assets, state);
  }

  /**
   * When the meshes moved again during a build (a drag), shows the built step
   * at once, so a long drag updates the image after every build rather than
   * only when it stops; the page's other edits go with it when they leave
   * the BVH as built (the meshes' materials, spheres, lights and the ground
   * always do). upload() then builds for the latest.
   */
  private showBuilt(snapshot: Scene, key: string, bvh: PrebuiltBvh): void {
    const { scene, assets } = this.current();
    if (meshState(scene, assets).key === key) return; // upload() takes it
    const mixed = { ...structuredClone(scene), meshes: snapshot.meshes };
    this.uploadedKey = key;
    this.built = null;
    this.tracer.setScene(meshState(mixed, assets).key === key ? mixed : snapshot, assets, { bvh });
  }

  private build(snapshot: Scene, assets: SceneAssets, state: MeshState): void {
    this.building = state.key;
    showState('building');
    const started = performance.now();
    buildBvhAsync(bvhInputs(snapshot, assets)).then(
      (packed) => {
        this.lastBuildMs = performance.now() - started;
        if (typeof document !== 'undefined') document.body.dataset.meshBuildMs = this.lastBuildMs.toFixed(0);
        const bvh = prebuiltBvh(snapshot, assets, packed);
        this.building = null;
        this.built = { key: state.key, bvh };
        this.showBuilt(snapshot, state.key, bvh);
        this.upload();
      },
      (error: Error) => {
        this.building = null;
        showState('failed');
        this.onError(`The meshes could not be prepared for rendering: ${error.message}`);
      },
    );
  }
}

/** For tests and benchmarks: whether the image shows the latest meshes (body[data-meshes]). */
function showState(state: 'building' | 'ready' | 'failed'): void {
  if (typeof document !== 'undefined') document.body.dataset.meshes = state;
}
