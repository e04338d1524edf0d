/**
 * Example scenes of the page beyond the presets of src/scene/presets (listed
 * in the example picker after them): those that use a bundled environment
 * map, a bundled model (meshControls.ts's meshExampleFiles) or bundled
 * texture images (exampleFiles/).
 */
import { bundledMapFile } from './bundledMaps';

/** Like test/fixtures/scenes/envmap.json, lit by the map alone. */
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
  // Like test/fixtures/scenes/conductor.json (version 3): named metals, eta and k given, a rough metal ground.
  metals: {
    version: 3,
    camera: { position: [0, 1.2, 5.0], target: [0, 0.45, 0], fov: 34 },
    image: { width: 640, height: 400 },
    environment: { map: bundledMapFile('sunset'), intensity: 0.7, rotation: 60 },
    ground: { material: { type: 'conductor', metal: 'Al', roughness: 0.35, color: [0.5, 0.5, 0.5] } },
    lights: [{ position: [-2, 3.5, 2.5], radius: 0.3, intensity: 30 }],
    spheres: [
      { center: [-2.0, 0.45, 0], radius: 0.45, material: { type: 'conductor', metal: 'Au' } },
      { center: [-1.0, 0.45, 0], radius: 0.45, material: { type: 'conductor', metal: 'Cu', roughness: 0.25 } },
      { center: [0.0, 0.45, 0], radius: 0.45, material: { type: 'conductor', metal: 'Ag', roughness: 0.5 } },
      { center: [1.0, 0.45, 0], radius: 0.45, material: { type: 'conductor', metal: 'Cr', roughness: 0.15 } },
      { center: [2.0, 0.45, 0], radius: 0.45, material: { type: 'conductor', eta: [0.2, 0.9, 1.1], k: [3.9, 2.45, 2.1], roughness: 0.7, color: [1, 0.9, 0.8] } },
    ],
  },
  // test/fixtures/scenes/principled.json (version 3: the principled material's lobes), lit by the bundled
  // sunset map instead of the fixture's sunset.hdr, a different file (as 'environment map' does for envmap.json).
  principled: {
    version: 3,
    image: { width: 192, height: 120 },
    camera: { position: [0, 1.3, 5.2], target: [0, 0.45, 0], fov: 34 },
    environment: { map: bundledMapFile('sunset'), intensity: 0.6, rotation: 120 },
    ground: { material: { type: 'principled', baseColor: [0.45, 0.45, 0.45], roughness: 0.7 } },
    lights: [
      { position: [2.5, 4, 3], radius: 0.4, intensity: 25 },
    ],
    spheres: [
      { center: [-2.0, 0.45, 0], radius: 0.45, material: { type: 'principled', baseColor: [1.0, 0.78, 0.34], metallic: 1, roughness: 0.3 } },
      { center: [-1.0, 0.45, 0], radius: 0.45, material: { type: 'principled', baseColor: '#c0392b', roughness: 0.4, specTint: 0.5 } },
      { center: [0.0, 0.45, 0], radius: 0.45, material: { type: 'principled', baseColor: [0.05, 0.15, 0.6], roughness: 0.6, clearcoat: 1, clearcoatGloss: 0.8 } },
      { center: [1.0, 0.45, 0], radius: 0.45, material: { type: 'principled', baseColor: [0.5, 0.2, 0.6], roughness: 0.9, sheen: 1, sheenTint: 0.5 } },
      { center: [2.0, 0.45, 0], radius: 0.45, material: { type: 'principled', baseColor: [0.9, 0.95, 1.0], roughness: 0.15, specTrans: 1, ior: 1.45 } },
    ],
  },
};

/** Example scenes with a bundled model, by the name shown in the example picker. */
export const MESH_EXAMPLES: Readonly<Record<string, unknown>> = {
  'bunny (model)': {
    version: 2,
    camera: { position: [0, 1.3, 4.6], target: [0, 0.6, 0], fov: 35 },
    image: { width: 256, height: 192 },
    environment: { color: [0.6, 0.7, 0.9], intensity: 0.5 },
    ground: { height: 0, material: { color: [0.6, 0.6, 0.6], roughness: 0.9 } },
    lights: [{ position: [2, 4, 3], radius: 0.5, intensity: 30 }],
    spheres: [{ center: [1.3, 0.35, 0.4], radius: 0.35, material: { type: 'dielectric', ior: 1.5 } }],
    meshes: [{ file: 'bunny.ply', position: [-0.1, 0, 0], rotation: [0, 20, 0], scale: 0.12, material: { color: [0.85, 0.8, 0.7], roughness: 0.45 } }],
  },
};

/**
 * Example scenes with bundled texture images and models
 * (exampleFiles/index.ts, loaded the first time one is opened), by the name
 * shown in the example picker.
 */
export const TEXTURE_EXAMPLES: Readonly<Record<string, { scene: unknown; files: () => Promise<Map<string, Blob>> }>> = {
  // test/fixtures/scenes/textured.json with its files named without folders, lit by the bundled studio
  // map: the fixture's studio.exr is the same 512 x 256 map, whose bundled copy is DWAB-compressed (decoded
  // texels differ by at most 0.012, mean 1.88).
  textured: {
    scene: {
      version: 3,
      image: { width: 192, height: 144 },
      camera: { position: [1.6, 1.5, 2.6], target: [0, 0.35, 0], fov: 40 },
      environment: { map: bundledMapFile('studio'), intensity: 0.45, rotation: 40 },
      ground: { material: { type: 'principled', baseColor: { image: 'checker.png', uv: { scale: [0.25, 0.25], rotation: 20 } }, roughness: { image: 'rough.png', channel: 'g', scale: 0.8 } } },
      meshes: [
        { file: 'uvbox.obj', position: [0, 0.35, 0], rotation: [0, 30, 0], scale: 0.7, material: { type: 'principled', baseColor: { image: 'grid.png' }, metallic: { image: 'rough.png', channel: 'b' }, roughness: 0.35 } },
        { file: 'uvbox.obj', position: [-0.9, 0.2, 0.6], rotation: [0, -15, 0], scale: 0.4, material: { type: 'principled', baseColor: [0.8, 0.8, 0.8], roughness: 0.3, metallic: 1, normalMap: { image: 'bumps.png' } } },
      ],
    },
    files: () => import('./exampleFiles').then((m) => m.texturedExampleFiles()),
  },
};
