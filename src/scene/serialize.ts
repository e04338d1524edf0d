/**
 * Scene -> scene-format JSON. The inverse of `parseScene`: every value is
 * written out explicitly (defaults included), colors as linear [r, g, b], so
 * `parseScene(serializeScene(s))` deep-equals `s` for every valid `s`.
 */
import type { Camera, Material, Scene, Vec3 } from './types';

export interface MaterialJson {
  color: Vec3;
  roughness: number;
}

export interface SceneJson {
  version: 1;
  camera: {
    position: Vec3;
    target: Vec3;
    up: Vec3;
    fov: number;
    aperture: number;
    /** Written only when the scene sets it; absent means the distance to the target. */
    focusDistance?: number;
  };
  image: { width: number; height: number };
  render: { maxBounces: number };
  /** Absent when the scene has none (black): the format's way of saying so. */
  environment?: { color: Vec3; intensity: number };
  /** Absent when the scene has no ground plane. */
  ground?: { height: number; material: MaterialJson };
  lights: { position: Vec3; radius: number; color: Vec3; intensity: number }[];
  spheres: { center: Vec3; radius: number; material: MaterialJson }[];
}

/** A fresh JSON-ready object (no references shared with `scene`), keys in the documented order. */
export function serializeScene(scene: Scene): SceneJson {
  const { environment, ground } = scene;
  return {
    version: 1,
    camera: cameraJson(scene.camera),
    image: { width: scene.image.width, height: scene.image.height },
    render: { maxBounces: scene.render.maxBounces },
    ...(environment ? { environment: { color: vec(environment.color), intensity: environment.intensity } } : {}),
    ...(ground ? { ground: { height: ground.height, material: materialJson(ground.material) } } : {}),
    lights: scene.lights.map((light) => ({
      position: vec(light.position),
      radius: light.radius,
      color: vec(light.color),
      intensity: light.intensity,
    })),
    spheres: scene.spheres.map((sphere) => ({
      center: vec(sphere.center),
      radius: sphere.radius,
      material: materialJson(sphere.material),
    })),
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

const materialJson = (material: Material): MaterialJson => ({
  color: vec(material.color),
  roughness: material.roughness,
});

const vec = (v: Vec3): Vec3 => [v[0], v[1], v[2]];
