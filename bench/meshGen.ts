/** Generated meshes for the mesh benchmarks: a bumpy latitude-longitude sphere of about N triangles, smooth, as PLY bytes and a scene. */
import { encodePly } from '../src/scene/mesh';
import { parseScene } from '../src/scene/schema';
import type { Scene, TriangleMesh } from '../src/scene/types';

export function bumpySphere(triangles: number): TriangleMesh {
  const rows = Math.round(Math.sqrt(triangles / 4));
  const cols = Math.round(triangles / (2 * rows));
  const positions = new Float32Array((rows + 1) * (cols + 1) * 3);
  for (let i = 0; i <= rows; i++) {
    for (let j = 0; j <= cols; j++) {
      const theta = (Math.PI * i) / rows;
      const phi = (2 * Math.PI * j) / cols;
      const r = 1 + 0.05 * Math.sin(13 * theta) * Math.cos(17 * phi);
      positions.set([r * Math.sin(theta) * Math.cos(phi), r * Math.cos(theta), r * Math.sin(theta) * Math.sin(phi)], (i * (cols + 1) + j) * 3);
    }
  }
  const indices = new Uint32Array(rows * cols * 6);
  let o = 0;
  for (let i = 0; i < rows; i++) {
    for (let j = 0; j < cols; j++) {
      const a = i * (cols + 1) + j;
      indices.set([a, a + cols + 1, a + 1, a + 1, a + cols + 1, a + cols + 2], o);
      o += 6;
    }
  }
  const normals = new Float32Array(positions.length);
  for (let v = 0; v < positions.length; v += 3) {
    const n = Math.hypot(positions[v], positions[v + 1], positions[v + 2]) || 1;
    for (let k = 0; k < 3; k++) normals[v + k] = positions[v + k] / n;
  }
  return { positions, normals, indices };
}

export const bumpySpherePly = (triangles: number): Uint8Array => encodePly(bumpySphere(triangles));

/** The seed scene's setting (ground, light, sky) with one generated mesh `file` standing on the ground. */
export function meshScene(file: string, width: number, height: number): Scene {
  return parseScene({
    version: 2,
    camera: { position: [0, 1.5, 6], target: [0, 0.8, 0], fov: 40 },
    image: { width, height },
    environment: { color: '#a0c0ff', intensity: 0.4 },
    ground: { height: 0, material: { color: [0.7, 0.7, 0.7], roughness: 1 } },
    lights: [{ position: [2, 4, 2], radius: 0.5, intensity: 40 }],
    meshes: [{ file, position: [0, 0.85, 0], scale: 0.8, material: { color: '#d04040', roughness: 0.3 } }],
  });
}
