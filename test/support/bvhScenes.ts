/** Triangle soups and meshes for the BVH tests (Node and browser). */
import type { BvhMeshInput } from '../../src/render/bvh/build';
import { random } from './random';

export { random } from './random';

/** `count` random triangles (sizes from tiny to large) in [-extent, extent]^3, every one its own 3 vertices. */
export function triangleSoup(count: number, seed: number, extent = 5, material = 0, smooth = false): BvhMeshInput {
  const rand = random(seed);
  const positions = new Float32Array(count * 9);
  for (let t = 0; t < count; t++) {
    const size = Math.pow(10, -2 + 2.5 * rand());
    const center = [0, 1, 2].map(() => (rand() * 2 - 1) * extent);
    for (let v = 0; v < 3; v++) for (let k = 0; k < 3; k++) positions[t * 9 + v * 3 + k] = center[k] + (rand() - 0.5) * size;
  }
  const normals = smooth ? positions.map(() => rand() - 0.5) : null;
  return { positions, normals, indices: Uint32Array.from({ length: count * 3 }, (_, i) => i), material };
}
