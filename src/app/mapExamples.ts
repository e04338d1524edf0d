/**
 * Example scenes of the page that use a bundled environment map (listed in
 * the example picker after the presets of src/scene/presets). Like
 * test/fixtures/scenes/envmap.json, lit by the map alone.
 */
import { bundledMapFile } from './bundledMaps';

export const MAP_EXAMPLES: Record<string, unknown> = {
  'environment map': {
    version: 2,
    camera: { position: [0, 1.4, 6], target: [0, 0.7, 0], fov: 38 },
    image: { width: 640, height: 480 },
    environment: { map: bundledMapFile('sunset'), intensity: 1, rotation: 30 },
    ground: { height: 0, material: { color: [0.6, 0.6, 0.6], roughness: 1 } },
    spheres: [
      { center: [-1.6, 0.7, 0], radius: 0.7, material: { color: [0.95, 0.95, 0.95], roughness: 0 } },
      { center: [0, 0.7, -0.4], radius: 0.7, material: { color: [0.9, 0.6, 0.3], roughness: 0.4 } },
      { center: [1.6, 0.7, 0], radius: 0.7, material: { type: 'dielectric', ior: 1.5 } },
    ],
  },
};
