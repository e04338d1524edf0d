/** CPU side of the triangle BVH: build, pack into textures, a TypeScript traversal for tests, a worker API for the page. */
export { buildBvh, MAX_BVH_DEPTH, MAX_LEAF_TRIANGLES, type Bvh, type BvhMeshInput } from './build';
export { packBvh, packBvhGroups, bvhBounds, BVH_TEXTURE_WIDTH, BVH_LAYER_ROWS, MAX_TRIANGLES, type PackedBvh, type TextureData, type LayeredTextureData } from './pack';
export { traverseBvh, bruteForce, type BvhHit } from './traverse';
export { groupMeshes, storedTriangles, trianglesIn, MAX_INSTANCES, INSTANCE_MIN_SAVED_TRIANGLES, type MeshGroups } from './groups';
export { buildAndPack, buildAndPackGroups } from './worker';
export { buildBvhAsync, stopBvhWorker } from './buildAsync';
