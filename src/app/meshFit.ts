/**
 * Where a newly added model goes, so the user sees it at once: turned Y-up
 * when its bounds say it was modelled Z-up, scaled to the scene, centred
 * under the camera's target and standing on the ground, and the camera
 * framed on it. The fit is an ordinary `position`/`rotation`/`scale` (the
 * file is not changed), so the user can edit or undo it. Pure: no DOM, no GL.
 */
import { meshBounds } from '../scene/picking';
import type { Camera, Mesh, Scene, TriangleMesh, Vec3 } from '../scene/types';

export interface MeshFit {
  position: Vec3;
  rotation: Vec3;
  scale: Vec3;
}

/** A model this much taller along z than along y (and taller than wide) was modelled Z-up. */
const Z_UP_RATIO = 1.2;
/** The model's largest side, as a fraction of the camera's distance to its target. */
const SIZE_OF_VIEW = 0.3;
/** Margin around the model's bounding sphere when framing it. */
const FRAME_MARGIN = 1.15;

/** glTF is Y-up by definition; other formats carry no convention, so their bounds decide. */
export function looksZUp(data: TriangleMesh, fileName: string): boolean {
  if (/\.(gltf|glb)$/i.test(fileName)) return false;
  const { min, max } = meshBounds(data);
  const [x, y, z] = [0, 1, 2].map((k) => max[k] - min[k]);
  return z > Z_UP_RATIO * y && z >= x;
}

/** Object-space bounds after the fit's rotation (0 or -90 degrees about x: (x, y, z) -> (x, z, -y)). */
function rotatedBounds(data: TriangleMesh, zUp: boolean): { min: Vec3; max: Vec3 } {
  const { min, max } = meshBounds(data);
  if (!zUp) return { min: [...min], max: [...max] };
  return { min: [min[0], min[2], -max[1]], max: [max[0], max[2], -min[1]] };
}

export function fitMesh(data: TriangleMesh, fileName: string, scene: Scene): MeshFit {
  const zUp = looksZUp(data, fileName);
  const { min, max } = rotatedBounds(data, zUp);
  const size = Math.max(max[0] - min[0], max[1] - min[1], max[2] - min[2]);
  const { position: eye, target } = scene.camera;
  const viewDistance = Math.hypot(target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]);
  const s = size > 0 ? (SIZE_OF_VIEW * viewDistance) / size : 1;
  const floor = scene.ground ? scene.ground.height : target[1] - (s * (max[1] - min[1])) / 2;
  // The bottom centre of the scaled, rotated bounds lands on the floor under the target.
  const position: Vec3 = [
    target[0] - (s * (min[0] + max[0])) / 2,
    floor - s * min[1],
    target[2] - (s * (min[2] + max[2])) / 2,
  ];
  return { position, rotation: [zUp ? -90 : 0, 0, 0], scale: [s, s, s] };
}

/** World-space bounding sphere of a placed mesh (of its transformed object-space box). */
export function worldBoundingSphere(mesh: Pick<Mesh, 'position' | 'rotation' | 'scale'>, data: TriangleMesh): { center: Vec3; radius: number } {
  const { min, max } = meshBounds(data);
  const local: Vec3 = [(min[0] + max[0]) / 2, (min[1] + max[1]) / 2, (min[2] + max[2]) / 2];
  const half = [0, 1, 2].map((k) => ((max[k] - min[k]) / 2) * mesh.scale[k]);
  return { center: toWorld(mesh, local), radius: Math.hypot(half[0], half[1], half[2]) };
}

/** The same view direction, aimed at the sphere's centre, far enough back to show it whole. */
export function frameCamera(camera: Camera, center: Vec3, radius: number, aspect: number): Camera {
  const dir = [0, 1, 2].map((k) => camera.target[k] - camera.position[k]);
  const length = Math.hypot(dir[0], dir[1], dir[2]) || 1;
  const halfV = (camera.fov * Math.PI) / 360;
  const halfH = Math.atan(Math.tan(halfV) * aspect);
  const distance = (FRAME_MARGIN * radius) / Math.sin(Math.min(halfV, halfH));
  const position = [0, 1, 2].map((k) => center[k] - (dir[k] / length) * distance) as Vec3;
  const framed: Camera = { ...structuredClone(camera), position, target: [...center] };
  if (camera.focusDistance !== undefined) framed.focusDistance = distance;
  return framed;
}

/** Object point to world: translate * Rz * Ry * Rx * scale (the format's order). */
function toWorld(mesh: Pick<Mesh, 'position' | 'rotation' | 'scale'>, p: Vec3): Vec3 {
  let v: Vec3 = [p[0] * mesh.scale[0], p[1] * mesh.scale[1], p[2] * mesh.scale[2]];
  const [ax, ay, az] = mesh.rotation.map((d) => (d * Math.PI) / 180);
  v = [v[0], v[1] * Math.cos(ax) - v[2] * Math.sin(ax), v[1] * Math.sin(ax) + v[2] * Math.cos(ax)];
  v = [v[0] * Math.cos(ay) + v[2] * Math.sin(ay), v[1], -v[0] * Math.sin(ay) + v[2] * Math.cos(ay)];
  v = [v[0] * Math.cos(az) - v[1] * Math.sin(az), v[0] * Math.sin(az) + v[1] * Math.cos(az), v[2]];
  return [v[0] + mesh.position[0], v[1] + mesh.position[1], v[2] + mesh.position[2]];
}
