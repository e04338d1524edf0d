/**
 * A scene around one model file, and the fitting and framing math the page
 * uses when a model is added. Where a model goes, so the user sees it at
 * once: turned Y-up when its bounds say it was modelled Z-up, scaled to the
 * view, centred under the camera's target and standing on the ground, and
 * the camera framed on it. The fit is an ordinary `position`/`rotation`/
 * `scale` (the file is not changed). `modelSceneDocument` builds the scene
 * the command line renders for `pathtrace render model.glb` (and prints for
 * `pathtrace scene model.glb`). Pure: no DOM, no GL, no files.
 */
import { DEFAULT_SCENE_JSON } from './presets';
import { meshBounds } from './picking';
import type { SceneJson } from './schema';
import { serializeScene } from './serialize';
import { meshToWorldMatrix } from './mesh/transform';
import type { GltfCamera } from './mesh/gltfCameras';
import type { Camera, ImageSize, Mesh, Scene, TriangleMesh, Vec3 } from './types';

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

/**
 * The placement of a model seen by `camera`: its largest side SIZE_OF_VIEW
 * of the view distance, its bottom centre under the camera's target, on the
 * ground at `groundHeight` (null: no ground, centred on the target).
 */
export function fitMeshToView(data: TriangleMesh, fileName: string, camera: Pick<Camera, 'position' | 'target'>, groundHeight: number | null): MeshFit {
  const zUp = looksZUp(data, fileName);
  const { min, max } = rotatedBounds(data, zUp);
  const size = Math.max(max[0] - min[0], max[1] - min[1], max[2] - min[2]);
  const { position: eye, target } = camera;
  const viewDistance = Math.hypot(target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]);
  const s = size > 0 ? (SIZE_OF_VIEW * viewDistance) / size : 1;
  const floor = groundHeight ?? target[1] - (s * (max[1] - min[1])) / 2;
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

/** The image size of a model's scene unless --width/--height say otherwise (the default scene's 4:3). */
export const MODEL_IMAGE: ImageSize = { width: 640, height: 480 };
/** The ground under a model: a neutral grey Lambertian plane at height 0. */
export const MODEL_GROUND = { height: 0, material: { type: 'standard', color: [0.5, 0.5, 0.5], roughness: 1 } } as const;
/** The bundled studio map, as the page names it (src/app/bundledMaps.ts). */
export const STUDIO_MAP = 'bundled/studio.exr';
/**
 * The studio map's irradiance on an upward surface is about 4.5 pi; at 0.2 a
 * white diffuse surface facing up shows about 0.9, under the display's 1.
 */
export const STUDIO_INTENSITY = 0.2;
/** Without a map (`--env none`): a uniform white sky, the look of a clay render (ambient occlusion). */
export const PLAIN_SKY = { color: [1, 1, 1] as Vec3, intensity: 0.8 };

export interface ModelSceneOptions {
  /** The model's path as the scene names it (relative to the scene's folder). */
  file: string;
  /** Its triangles, decoded: the fit reads their bounds. */
  data: TriangleMesh;
  image: ImageSize;
  /** An environment map's path as the scene names it, or null for PLAIN_SKY. */
  environmentMap: string | null;
  /** The map's intensity (default 1; the studio map wants STUDIO_INTENSITY). */
  environmentIntensity?: number;
  /** A camera of the file (perspective, placed by a node) to look through instead of the framed default. */
  camera?: GltfCamera;
}

/**
 * The scene JSON (version 3) for one model: the mesh with no `material`
 * (version 3: the file's own materials), fitted on the ground in front of
 * the default scene's camera and framed by it (or seen by the file's camera),
 * lit by the map. No other light: the map lights it as the map was made.
 */
export function modelSceneDocument(options: ModelSceneOptions): SceneJson {
  const base = (DEFAULT_SCENE_JSON as { camera: { position: Vec3; target: Vec3; fov: number } }).camera;
  const defaultCamera: Camera = { position: [...base.position], target: [...base.target], up: [0, 1, 0], fov: base.fov, aperture: 0 };
  const fit = fitMeshToView(options.data, options.file, defaultCamera, MODEL_GROUND.height);
  const bounds = worldBoundingSphere(fit, options.data);
  const aspect = options.image.width / options.image.height;
  const camera = options.camera ? gltfCameraInScene(options.camera, fit, bounds.center) : frameCamera(defaultCamera, bounds.center, bounds.radius, aspect);
  const environment = options.environmentMap === null
    ? { color: [...PLAIN_SKY.color] as Vec3, intensity: PLAIN_SKY.intensity }
    : { map: options.environmentMap, intensity: options.environmentIntensity ?? 1, rotation: 0 };
  return {
    version: 3,
    camera: { position: camera.position, target: camera.target, up: camera.up, fov: camera.fov, aperture: 0 },
    image: { width: options.image.width, height: options.image.height },
    environment,
    ground: structuredClone(MODEL_GROUND) as SceneJson['ground'],
    lights: [],
    spheres: [],
    meshes: [{ file: options.file, position: fit.position, rotation: fit.rotation, scale: fit.scale }],
  } as SceneJson;
}

/**
 * A glTF camera after the mesh's placement: the file's camera lives in the
 * file's space (which the mesh decoder keeps as the object space), so the
 * fit's matrix takes it into the scene. Looks down its -z, up its +y; the
 * target is the point on its axis nearest the model's centre (where it
 * focuses, were the aperture opened), one unit ahead if that is behind it.
 */
export function gltfCameraInScene(camera: GltfCamera, fit: MeshFit, modelCenter: Vec3): Camera {
  if (camera.type !== 'perspective' || !camera.world) throw new Error('the camera must be perspective and placed by a node');
  const m = multiply(meshToWorldMatrix(fit), camera.world);
  const apply = (v: [number, number, number, number]) => [0, 1, 2].map((r) => m[r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2] + m[12 + r] * v[3]) as Vec3;
  const position = apply([0, 0, 0, 1]);
  const forward = normalize(apply([0, 0, -1, 0]));
  const up = normalize(apply([0, 1, 0, 0]));
  const ahead = [0, 1, 2].reduce((sum, k) => sum + (modelCenter[k] - position[k]) * forward[k], 0);
  const distance = ahead > 1e-6 ? ahead : 1;
  const target = [0, 1, 2].map((k) => position[k] + forward[k] * distance) as Vec3;
  return { position, target, up, fov: ((camera.yfov ?? 0) * 180) / Math.PI, aperture: 0 };
}

function multiply(a: ArrayLike<number>, b: ArrayLike<number>): Float64Array {
  const out = new Float64Array(16);
  for (let c = 0; c < 4; c++) {
    for (let r = 0; r < 4; r++) {
      let sum = 0;
      for (let k = 0; k < 4; k++) sum += a[k * 4 + r] * b[c * 4 + k];
      out[c * 4 + r] = sum;
    }
  }
  return out;
}

function normalize(v: Vec3): Vec3 {
  const length = Math.hypot(v[0], v[1], v[2]) || 1;
  return [v[0] / length, v[1] / length, v[2] / length];
}

/**
 * A parsed model scene as JSON with every key written out (serializeScene),
 * except the meshes' `material`: a model scene's mesh has none, so in
 * version 3 it keeps the file's own materials.
 */
export function modelSceneJson(scene: Scene): SceneJson {
  const json = serializeScene(scene);
  const meshes = (json.meshes ?? []).map((mesh) => {
    const { material: _material, ...rest } = mesh as Record<string, unknown>;
    return rest;
  });
  return { ...json, meshes } as SceneJson;
}
