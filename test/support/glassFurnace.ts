/**
 * The glass white furnace scene, shared by the test and the script that
 * renders Mitsuba's fixtures for it: a unit dielectric sphere in a uniform
 * white environment, no ground, no lights, 64 bounces (a path that stays
 * inside longer is lost in both renderers alike).
 */
import { parseSceneText } from '../../src/scene/schema';
import type { Scene, Vec3 } from '../../src/scene/types';

export const GLASS_FURNACE_ROUGHNESS = [0.3, 0.6, 1] as const;
export const GLASS_FURNACE_SIZE = { width: 64, height: 64 } as const;

export function glassFurnaceScene(roughness: number, color: Vec3 = [1, 1, 1], ior = 1.5): Scene {
  return parseSceneText(JSON.stringify({
    version: 2,
    camera: { position: [0, 0, 4], target: [0, 0, 0], fov: 40 },
    image: GLASS_FURNACE_SIZE,
    render: { maxBounces: 64 },
    environment: { color: [1, 1, 1], intensity: 1 },
    lights: [],
    spheres: [{ center: [0, 0, 0], radius: 1, material: { type: 'dielectric', color, ior, roughness } }],
  }));
}
