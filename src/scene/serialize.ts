/**
 * Scene -> scene-format JSON. The inverse of `parseScene`: every value is
 * written out explicitly (defaults included), colors as linear [r, g, b], so
 * `parseScene(serializeScene(s))` deep-equals `s` for every valid `s`. A
 * scene that uses nothing of a later version is written as a document of
 * the earliest version that holds it (version 1: no material `type`, no
 * `meshes`), so it reads the same in older readers.
 */
import { lightJson } from '../lights/registry';
import { materialJson } from '../materials/registry';
import type { SceneJson } from './schema';
import type { Camera, Environment, Material, Mesh, Scene, Vec3 } from './types';
import { requiredVersion } from './version';

export type { SceneJson };

/** A fresh JSON-ready object (no references shared with `scene`), keys in the documented order. */
export function serializeScene(scene: Scene): SceneJson {
  const { environment, ground } = scene;
  const version = Math.max(scene.version, requiredVersion(scene)) as 1 | 2 | 3;
  const material = (m: Material) => materialJson(m, version);
  return {
    version,
    camera: cameraJson(scene.camera),
    image: { width: scene.image.width, height: scene.image.height },
    render: { maxBounces: scene.render.maxBounces },
    ...(environment ? { environment: environmentJson(environment) } : {}),
    ...(ground ? { ground: { height: ground.height, material: material(ground.material) } } : {}),
    lights: scene.lights.map((light) => lightJson(light, version)) as SceneJson['lights'],
    spheres: scene.spheres.map((sphere) => ({
      center: vec(sphere.center),
      radius: sphere.radius,
      material: material(sphere.material),
    })),
    ...(version >= 2 ? { meshes: scene.meshes.map((mesh) => meshJson(mesh)) } : {}),
  };
}

/**
 * JSON text for a scene, two-space indented with every [x, y, z] on one line,
 * the way the example scenes are written.
 */
export function stringifyScene(scene: Scene): string {
  const text = JSON.stringify(serializeScene(scene), null, 2);
  // Fold arrays of three numbers, which JSON.stringify spreads over four lines.
  return text.replace(/\[\s+(-?[\d.eE+-]+),\s+(-?[\d.eE+-]+),\s+(-?[\d.eE+-]+)\s+\]/g, '[$1, $2, $3]');
}

function cameraJson(camera: Camera): SceneJson['camera'] {
  const json: SceneJson['camera'] = {
    position: vec(camera.position),
    target: vec(camera.target),
    up: vec(camera.up),
    fov: camera.fov,
    aperture: camera.aperture,
  };
  if (camera.focusDistance !== undefined) json.focusDistance = camera.focusDistance;
  return json;
}

function environmentJson(e: Environment): NonNullable<SceneJson['environment']> {
  return 'map' in e ? { map: e.map, intensity: e.intensity, rotation: e.rotation } : { color: vec(e.color), intensity: e.intensity };
}

function meshJson(mesh: Mesh) {
  return {
    file: mesh.file,
    // Without the key (version 3) the mesh wears its file's own materials.
    ...(mesh.material ? { material: materialJson(mesh.material, 2) } : {}),
    position: vec(mesh.position),
    rotation: vec(mesh.rotation),
    scale: vec(mesh.scale),
  };
}

const vec = (v: Vec3): Vec3 => [v[0], v[1], v[2]];
