import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import {
  DEFAULT_SCENE_JSON,
  MAX_LIGHTS,
  MAX_MESHES,
  MAX_REPORTED_ISSUES,
  MAX_SCENE_BYTES,
  MAX_SPHERES,
  PRESETS,
  PRESET_NAMES,
  SceneError,
  defaultScene,
  parseScene,
  parseSceneText,
  safeParseScene,
  safeParseSceneText,
  serializeScene,
  stringifyScene,
  type Scene,
  type SceneIssue,
} from '../../src/scene';

const FIXTURES = join(__dirname, '../fixtures/scenes');
const fixtureNames = readdirSync(FIXTURES)
  .filter((file) => file.endsWith('.json'))
  .map((file) => file.replace(/\.json$/, ''));
const fixture = (name: string): Record<string, any> => JSON.parse(readFileSync(join(FIXTURES, `${name}.json`), 'utf8'));

const minimal = () => ({ camera: { position: [0, 1, 5], target: [0, 0, 0] } });

/** A copy of `base` with `edit` applied, for building bad scenes. */
function edited(edit: (scene: Record<string, any>) => void, base = fixture('seed')): unknown {
  const copy = structuredClone(base);
  edit(copy);
  return copy;
}

/** The issues of a scene that must be rejected; fails the test if it is accepted. */
function issuesOf(input: unknown): SceneIssue[] {
  const result = safeParseScene(input);
  if (result.ok) throw new Error('expected the scene to be rejected');
  return result.issues;
}

function thrown(run: () => unknown): SceneError {
  try {
    run();
  } catch (error) {
    expect(error).toBeInstanceOf(SceneError);
    return error as SceneError;
  }
  throw new Error('expected a SceneError');
}

describe('valid scenes', () => {
  it('finds the twenty-four fixtures', () => {
    expect(fixtureNames.sort()).toEqual([
      'bench', 'bunny', 'conductor', 'emissive', 'emissive-mesh', 'emissive-tilted-normals', 'envmap', 'furnace', 'glass', 'glossy', 'gltf-materials', 'instanced',
      'light-directional', 'light-disk', 'light-many', 'light-point', 'light-rectangle', 'light-spot', 'lights', 'mirrors', 'principled', 'seed', 'small-light',
      'textured',
    ]);
  });

  it.each(fixtureNames)('parses %s, keeping its values', (name) => {
    const json = fixture(name);
    const scene = parseScene(json);
    expect(scene.camera.position).toEqual(json.camera.position);
    expect(scene.image).toEqual(json.image);
    expect(scene.render).toEqual(json.render ?? { maxBounces: 6 });
    expect(scene.spheres.map((s) => s.center)).toEqual((json.spheres ?? []).map((s: { center: number[] }) => s.center));
    expect(scene.lights).toHaveLength(json.lights?.length ?? 0);
    expect(scene.meshes).toHaveLength(json.meshes?.length ?? 0);
    expect(scene.version).toBe(json.version);
  });

  it.each(fixtureNames)('round-trips %s through serializeScene and JSON text', (name) => {
    const scene = parseScene(fixture(name));
    expect(parseScene(serializeScene(scene))).toStrictEqual(scene);
    expect(parseSceneText(JSON.stringify(serializeScene(scene)))).toStrictEqual(scene);
    expect(parseSceneText(stringifyScene(scene))).toStrictEqual(scene);
  });

  it('serializes every value explicitly, colors as linear arrays', () => {
    const scene = parseScene({ ...minimal(), spheres: [{ center: [0, 0, 0], radius: 1, material: { color: '#ffffff' } }] });
    expect(serializeScene(scene)).toStrictEqual({
      version: 1,
      camera: { position: [0, 1, 5], target: [0, 0, 0], up: [0, 1, 0], fov: 40, aperture: 0 },
      image: { width: 640, height: 480 },
      render: { maxBounces: 6 },
      lights: [],
      spheres: [{ center: [0, 0, 0], radius: 1, material: { color: [1, 1, 1], roughness: 1 } }],
    });
  });

  it('writes vectors on one line in stringifyScene', () => {
    expect(stringifyScene(defaultScene())).toContain('"position": [0, 2.2, 7.5]');
  });

  it('fills every default of a minimal scene', () => {
    expect(parseScene(minimal())).toStrictEqual({
      version: 1,
      camera: { position: [0, 1, 5], target: [0, 0, 0], up: [0, 1, 0], fov: 40, aperture: 0 },
      image: { width: 640, height: 480 },
      render: { maxBounces: 6 },
      environment: null,
      ground: null,
      lights: [],
      spheres: [],
      meshes: [],
    } satisfies Scene);
  });

  it('fills the defaults inside objects', () => {
    const scene = parseScene({
      ...minimal(),
      environment: {},
      ground: {},
      lights: [{ position: [0, 5, 0], radius: 0.5 }],
      spheres: [
        { center: [0, 1, 0], radius: 1 },
        { center: [2, 1, 0], radius: 1, material: {} },
        { center: [4, 1, 0], radius: 1, material: { roughness: 0.2 } },
      ],
    });
    const defaultMaterial = { type: 'standard', color: [0.8, 0.8, 0.8], roughness: 1 };
    expect(scene.environment).toStrictEqual({ color: [1, 1, 1], intensity: 1 });
    expect(scene.ground).toStrictEqual({ height: 0, material: defaultMaterial });
    expect(scene.lights).toStrictEqual([{ type: 'sphere', position: [0, 5, 0], radius: 0.5, color: [1, 1, 1], intensity: 1 }]);
    expect(scene.spheres.map((s) => s.material)).toStrictEqual([
      defaultMaterial,
      defaultMaterial,
      { type: 'standard', color: [0.8, 0.8, 0.8], roughness: 0.2 },
    ]);
  });

  it('leaves focusDistance out unless given, and keeps it when given', () => {
    expect('focusDistance' in parseScene(minimal()).camera).toBe(false);
    const camera = { ...minimal().camera, focusDistance: 3, aperture: 0.1, up: [0, 0, 1], fov: 60 };
    expect(parseScene({ camera }).camera).toStrictEqual({ ...camera, up: [0, 0, 1] });
  });

  it('accepts null for environment and ground, meaning none', () => {
    const scene = parseScene({ ...minimal(), environment: null, ground: null });
    expect(scene.environment).toBeNull();
    expect(scene.ground).toBeNull();
  });

  it('reads "#rrggbb" colors as sRGB, in either case', () => {
    const scene = parseScene({
      ...minimal(),
      environment: { color: '#FFFFFF' },
      lights: [{ position: [0, 5, 0], radius: 1, color: '#808080' }],
      spheres: [{ center: [0, 0, 0], radius: 1, material: { color: '#000000' } }],
    });
    expect(scene.environment && 'color' in scene.environment && scene.environment.color).toEqual([1, 1, 1]);
    expect(scene.lights[0].color[0]).toBeCloseTo(0.2158605, 7);
    expect((scene.spheres[0].material as { color: unknown }).color).toEqual([0, 0, 0]);
  });

  it('accepts values at the edges of their ranges', () => {
    const scene = parseScene({
      camera: { position: [-1e6, 1e6, 0], target: [0, 0, 0], fov: 179.9, aperture: 0, up: [1e-3, 1, 0] },
      image: { width: 1, height: 8192 },
      render: { maxBounces: 64 },
      environment: { color: [0, 0, 0], intensity: 0 },
      ground: { height: -1e6, material: { color: [0, 1, 0], roughness: 0 } },
      lights: [{ position: [0, 0, 0], radius: 1e6, color: [1e12, 0, 0], intensity: 1e12 }],
      spheres: [{ center: [0, 0, 0], radius: 1e-9 }],
    });
    expect(scene.render.maxBounces).toBe(64);
  });

  it('accepts an up vector parallel to the view direction', () => {
    expect(() => parseScene({ camera: { position: [0, 5, 0], target: [0, 0, 0] } })).not.toThrow();
  });

  it('accepts exactly the maximum numbers of spheres and lights', () => {
    const sphere = { center: [0, 0, 0], radius: 1 };
    const light = { position: [0, 5, 0], radius: 1 };
    const scene = parseScene({
      ...minimal(),
      spheres: Array(MAX_SPHERES).fill(sphere),
      lights: Array(MAX_LIGHTS).fill(light),
    });
    expect(scene.spheres).toHaveLength(MAX_SPHERES);
    expect(scene.lights).toHaveLength(MAX_LIGHTS);
  });

  it('accepts exactly the maximum number of meshes', () => {
    const scene = parseScene({ ...minimal(), version: 2, meshes: Array(MAX_MESHES).fill({ file: 'a.obj' }) });
    expect(scene.meshes).toHaveLength(MAX_MESHES);
  });

  it('returns a fresh object that shares nothing with the input', () => {
    const input = fixture('glossy');
    const scene = parseScene(input);
    const inputObjects = new Set<unknown>();
    const collect = (value: unknown, into: Set<unknown>) => {
      if (typeof value !== 'object' || value === null) return;
      into.add(value);
      Object.values(value).forEach((child) => collect(child, into));
    };
    collect(input, inputObjects);
    const sceneObjects = new Set<unknown>();
    collect(scene, sceneObjects);
    for (const object of sceneObjects) expect(inputObjects.has(object)).toBe(false);
    expect(Object.getPrototypeOf(scene)).toBe(Object.prototype);
    // Defaults are not shared between two parses either.
    const a = parseScene(minimal());
    const b = parseScene(minimal());
    expect(a.camera.up).not.toBe(b.camera.up);
  });

  it('turns -0 into 0', () => {
    const scene = parseScene({ camera: { position: [-0, 1, 5], target: [0, 0, 0] } });
    expect(Object.is(scene.camera.position[0], 0)).toBe(true);
  });
});

describe('presets', () => {
  it('are copies of the fixture scenes (all but those that need map or mesh files)', () => {
    expect([...PRESET_NAMES].sort()).toEqual(fixtureNames.filter((name) => !(['bench', 'bunny', 'conductor', 'envmap', 'gltf-materials', 'emissive-mesh', 'emissive-tilted-normals', 'instanced', 'lights', 'principled', 'textured'].includes(name) || name.startsWith('light-'))).sort());
    for (const name of PRESET_NAMES) expect(PRESETS[name]).toEqual(fixture(name));
  });

  it('all parse', () => {
    for (const name of PRESET_NAMES) expect(() => parseScene(PRESETS[name])).not.toThrow();
  });

  it('make seed the default scene, fresh on each call', () => {
    expect(DEFAULT_SCENE_JSON).toEqual(fixture('seed'));
    const a = defaultScene();
    expect(a).toStrictEqual(parseScene(fixture('seed')));
    a.spheres.length = 0;
    expect(defaultScene().spheres).toHaveLength(5);
  });

  it('cannot be modified by accident', () => {
    expect(Object.isFrozen(PRESETS)).toBe(true);
    expect(Object.isFrozen((PRESETS.seed as any).camera.position)).toBe(true);
  });
});

/** [description, input, expected path, expected message (substring)] */
const BAD_SCENES: [string, unknown, string, string][] = [
  ['a number instead of a scene', 42, '', 'must be an object'],
  ['an array instead of a scene', [], '', 'must be an object'],
  ['null', null, '', 'must be an object'],
  ['missing camera', {}, 'camera', 'required'],
  ['camera not an object', { camera: 'front' }, 'camera', 'must be an object'],
  ['missing camera.target', { camera: { position: [0, 0, 1] } }, 'camera.target', 'required'],
  ['version 4', edited((s) => (s.version = 4)), 'version', 'must be 1, 2 or 3'],
  ['version "1"', edited((s) => (s.version = '1')), 'version', 'must be 1, 2 or 3'],
  ['a point with two numbers', edited((s) => (s.camera.position = [0, 1])), 'camera.position', 'must be [x, y, z]'],
  ['a point with four numbers', edited((s) => (s.spheres[1].center = [0, 1, 2, 3])), 'spheres[1].center', 'must be [x, y, z]'],
  ['a point as a string', edited((s) => (s.lights[0].position = '0 1 2')), 'lights[0].position', 'must be [x, y, z]'],
  ['a string coordinate', edited((s) => (s.camera.target[1] = '0.8')), 'camera.target[1]', 'must be a number'],
  ['a NaN coordinate', edited((s) => (s.camera.position[0] = NaN)), 'camera.position[0]', 'must be a finite number'],
  ['an infinite radius', edited((s) => (s.spheres[0].radius = Infinity)), 'spheres[0].radius', 'must be a finite number'],
  ['a coordinate beyond 1e6', edited((s) => (s.spheres[0].center[2] = -2e6)), 'spheres[0].center[2]', 'must be >= -1e6'],
  ['a radius beyond 1e6', edited((s) => (s.spheres[0].radius = 1e7)), 'spheres[0].radius', 'must be <= 1e6'],
  ['zero sphere radius', edited((s) => (s.spheres[2].radius = 0)), 'spheres[2].radius', 'must be > 0'],
  ['negative light radius', edited((s) => (s.lights[0].radius = -1)), 'lights[0].radius', 'must be > 0'],
  ['negative intensity', edited((s) => (s.lights[0].intensity = -1)), 'lights[0].intensity', 'must be >= 0'],
  ['huge intensity', edited((s) => (s.environment.intensity = 1e300)), 'environment.intensity', 'must be <= 1e12'],
  ['roughness above 1', edited((s) => (s.spheres[2].material.roughness = 1.5)), 'spheres[2].material.roughness', 'must be <= 1'],
  ['negative roughness', edited((s) => (s.ground.material.roughness = -0.1)), 'ground.material.roughness', 'must be >= 0'],
  ['albedo above 1', edited((s) => (s.spheres[0].material.color = [1.2, 0, 0])), 'spheres[0].material.color[0]', 'must be <= 1'],
  ['negative emission', edited((s) => (s.lights[0].color = [1, -1, 1])), 'lights[0].color[1]', 'must be >= 0'],
  ['negative environment', edited((s) => (s.environment.color = [0, 0, -0.5])), 'environment.color[2]', 'must be >= 0'],
  ['hex color with 3 digits', edited((s) => (s.spheres[0].material.color = '#fff')), 'spheres[0].material.color', 'must be "#rrggbb" or [r, g, b]'],
  ['hex color without #', edited((s) => (s.spheres[0].material.color = 'ff0000')), 'spheres[0].material.color', 'must be "#rrggbb" or [r, g, b]'],
  ['hex color with a bad digit', edited((s) => (s.lights[0].color = '#12345g')), 'lights[0].color', 'must be "#rrggbb" or [r, g, b]'],
  ['a color name', edited((s) => (s.environment.color = 'red')), 'environment.color', 'must be "#rrggbb" or [r, g, b]'],
  ['a color with 4 channels', edited((s) => (s.environment.color = [1, 1, 1, 1])), 'environment.color', 'must be "#rrggbb" or [r, g, b]'],
  ['fov of 0', edited((s) => (s.camera.fov = 0)), 'camera.fov', 'must be > 0'],
  ['fov of 180', edited((s) => (s.camera.fov = 180)), 'camera.fov', 'must be < 180'],
  ['negative aperture', edited((s) => (s.camera.aperture = -0.1)), 'camera.aperture', 'must be >= 0'],
  ['zero focus distance', edited((s) => (s.camera.focusDistance = 0)), 'camera.focusDistance', 'must be > 0'],
  ['null focus distance', edited((s) => (s.camera.focusDistance = null)), 'camera.focusDistance', 'must be a number'],
  ['target at the position', edited((s) => (s.camera.target = [...s.camera.position])), 'camera.target', 'must differ from camera.position'],
  ['zero up vector', edited((s) => (s.camera.up = [0, 0, 0])), 'camera.up', 'must not be zero length'],
  ['fractional width', edited((s) => (s.image.width = 320.5)), 'image.width', 'must be an integer'],
  ['zero height', edited((s) => (s.image.height = 0)), 'image.height', 'must be >= 1'],
  ['oversized image', edited((s) => (s.image.width = 10000)), 'image.width', 'must be <= 8192'],
  ['image without height', edited((s) => (s.image = { width: 100 })), 'image.height', 'required'],
  ['fractional maxBounces', edited((s) => (s.render.maxBounces = 2.5)), 'render.maxBounces', 'must be an integer'],
  ['negative maxBounces', edited((s) => (s.render.maxBounces = -1)), 'render.maxBounces', 'must be >= 0'],
  ['maxBounces above the limit', edited((s) => (s.render.maxBounces = 65)), 'render.maxBounces', 'must be <= 64'],
  ['maxBounces as a string', edited((s) => (s.render.maxBounces = '6')), 'render.maxBounces', 'must be a number'],
  ['ground height as a string', edited((s) => (s.ground.height = 'low')), 'ground.height', 'must be a number'],
  ['ground as an array', edited((s) => (s.ground = [])), 'ground', 'must be an object'],
  ['spheres as an object', edited((s) => (s.spheres = {})), 'spheres', 'must be an array'],
  ['a sphere as a number', edited((s) => (s.spheres[3] = 7)), 'spheres[3]', 'must be an object'],
  ['a sphere without radius', edited((s) => delete s.spheres[4].radius), 'spheres[4].radius', 'required'],
  ['too many spheres', edited((s) => (s.spheres = Array(MAX_SPHERES + 1).fill(s.spheres[0]))), 'spheres', `at most ${MAX_SPHERES} spheres`],
  ['too many lights', edited((s) => (s.lights = Array(MAX_LIGHTS + 1).fill(s.lights[0]))), 'lights', `at most ${MAX_LIGHTS} lights`],
  ['too many meshes', v2((s) => (s.meshes = Array(MAX_MESHES + 1).fill({ file: 'a.obj' }))), 'meshes', `at most ${MAX_MESHES} meshes`],
  ['an unknown top-level key', edited((s) => (s.background = 1)), 'background', 'unknown key'],
  ['an unknown sphere key', edited((s) => (s.spheres[0].colour = [1, 0, 0])), 'spheres[0].colour', 'unknown key'],
  ['an unknown material key', edited((s) => (s.spheres[1].material.metal = true)), 'spheres[1].material.metal', 'unknown key'],
  ['an unknown camera key', edited((s) => (s.camera.zoom = 2)), 'camera.zoom', 'unknown key'],
  ['an unknown key with a space', edited((s) => (s.image['my width'] = 2)), 'image["my width"]', 'unknown key'],
  ['a __proto__ key', JSON.parse('{"camera":{"position":[0,0,1],"target":[0,0,0]},"__proto__":{}}'), '__proto__', 'unknown key'],
  // Version 2.
  ['a material type in a version-1 document', edited((s) => (s.spheres[0].material.type = 'standard')), 'spheres[0].material.type', 'requires "version": 2'],
  ['emission in a version-1 document', edited((s) => (s.spheres[1].material.emission = {})), 'spheres[1].material.emission', 'requires "version": 2'],
  ['a map in a version-1 document', edited((s) => (s.environment = { map: 'sky.hdr' })), 'environment.map', 'requires "version": 2'],
  ['meshes in a version-1 document', edited((s) => (s.meshes = [])), 'meshes', 'requires "version": 2'],
  ['an unknown material type', v2((s) => (s.spheres[0].material.type = 'glass')), 'spheres[0].material.type', 'must be "standard" or "dielectric" or "conductor"'],
  ['a dielectric ground', v2((s) => (s.ground.material = { type: 'dielectric' })), 'ground.material.type', 'must not be "dielectric" or "principled" with specTrans above 0 on the ground'],
  ['an emissive ground', v2((s) => (s.ground.material.emission = { intensity: 2 })), 'ground.material.emission', 'is not allowed on the ground'],
  ['ior below 1.01', v2((s) => (s.spheres[0].material = { type: 'dielectric', ior: 1 })), 'spheres[0].material.ior', 'must be >= 1.01'],
  ['ior above 4', v2((s) => (s.spheres[0].material = { type: 'dielectric', ior: 4.5 })), 'spheres[0].material.ior', 'must be <= 4'],
  ['ior on a standard material', v2((s) => (s.spheres[0].material.ior = 1.5)), 'spheres[0].material.ior', 'unknown key for this type'],
  ['negative emission intensity', v2((s) => (s.spheres[0].material.emission = { intensity: -1 })), 'spheres[0].material.emission.intensity', 'must be >= 0'],
  ['a map that is not a string', v2((s) => (s.environment = { map: 3 })), 'environment.map', 'must be a string'],
  ['a color beside a map', v2((s) => (s.environment = { map: 'a.hdr', color: [1, 1, 1] })), 'environment.color', 'unknown key for this type'],
  ['a mesh without a file', v2((s) => (s.meshes = [{}])), 'meshes[0].file', 'required'],
  ['a zero mesh scale', v2((s) => (s.meshes = [{ file: 'a.obj', scale: [1, 0, 1] }])), 'meshes[0].scale[1]', 'must be > 0'],
];

/** A version-2 copy of the seed scene with `edit` applied. */
function v2(edit: (scene: Record<string, any>) => void): unknown {
  return edited((s) => {
    s.version = 2;
    edit(s);
  });
}

describe('invalid scenes', () => {
  it.each(BAD_SCENES)('rejects %s', (_, input, path, message) => {
    const issues = issuesOf(input);
    expect(issues).toContainEqual({ path, message: expect.stringContaining(message) });
    const error = thrown(() => parseScene(input));
    expect(error.message).toContain(`${path === '' ? 'scene' : path}: ${message}`);
    expect(error.issues).toEqual(issues);
  });

  it('reports every error at once, each with its path', () => {
    const input = edited((s) => {
      s.version = 4;
      s.camera.fov = 200;
      s.camera.target = [...s.camera.position];
      s.image.width = -5;
      s.spheres[2].material.roughness = 3;
      s.spheres[4].material.color = '#12';
      s.lights[0].intensity = NaN;
      s.extra = true;
    });
    const error = thrown(() => parseScene(input));
    expect(error.issues.map((issue) => issue.path).sort()).toEqual(
      [
        'version',
        'camera.fov',
        'camera.target',
        'image.width',
        'spheres[2].material.roughness',
        'spheres[4].material.color',
        'lights[0].intensity',
        'extra',
      ].sort(),
    );
    expect(error.message.split('\n')).toHaveLength(8);
    expect(error.message).toContain('spheres[2].material.roughness: must be <= 1');
  });

  it('checks the camera target even when other camera fields are wrong', () => {
    const paths = issuesOf({ camera: { position: [1, 1, 1], target: [1, 1, 1], fov: -1, lens: 1 } }).map((i) => i.path);
    expect(paths).toEqual(expect.arrayContaining(['camera.fov', 'camera.lens', 'camera.target']));
  });

  it('reports one message per value', () => {
    const issues = issuesOf(edited((s) => (s.image.width = 1e20)));
    expect(issues).toEqual([{ path: 'image.width', message: 'must be <= 8192' }]);
  });

  it('suggests the allowed key for a likely typo', () => {
    const messages = issuesOf(
      edited((s) => {
        s.camera.focus_distance = 1;
        s.spheres[0].raduis = 1;
        s.ground.material.colour = [1, 1, 1];
      }),
    ).map((issue) => `${issue.path}: ${issue.message}`);
    expect(messages).toContain('camera.focus_distance: unknown key (did you mean "focusDistance"?)');
    expect(messages).toContain('spheres[0].raduis: unknown key (did you mean "radius"?)');
    expect(messages).toContain('ground.material.colour: unknown key (did you mean "color"?)');
  });

  it('caps the number of issues it reports', () => {
    const many = Object.fromEntries(Array.from({ length: 500 }, (_, i) => [`key${i}`, i]));
    const issues = issuesOf({ ...minimal(), ...many });
    expect(issues).toHaveLength(MAX_REPORTED_ISSUES + 1);
    expect(issues.at(-1)).toEqual({ path: '', message: '400 more problems not shown' });
  });

  it('shortens very long keys in paths', () => {
    const [issue] = issuesOf({ ...minimal(), ['k'.repeat(10_000)]: 1 });
    expect(issue.path.length).toBeLessThan(60);
  });
});

describe('hostile inputs', () => {
  const hostile: [string, () => unknown][] = [
    ['a getter that throws', () => ({ get camera() { throw new Error('boom'); } })],
    ['a proxy that throws', () => new Proxy({}, { ownKeys() { throw new Error('no keys'); }, get() { throw new Error('no'); } })],
    ['a million spheres', () => ({ ...minimal(), spheres: Array(1e6).fill({}) })],
    ['a sparse array of length 2^32 - 1', () => ({ ...minimal(), lights: new Array(2 ** 32 - 1) })],
    ['deeply nested arrays', () => {
      let deep: unknown = [];
      for (let i = 0; i < 100_000; i++) deep = [deep];
      return { camera: { position: deep, target: deep }, spheres: [deep], extra: deep };
    }],
    ['a long string', () => ({ ...minimal(), environment: { color: '#'.padEnd(1e6, 'f') } })],
    ['a function', () => () => 1],
    ['a symbol', () => Symbol('scene')],
    ['a bigint coordinate', () => ({ camera: { position: [0n, 0, 1], target: [0, 0, 0] } })],
    ['a Map', () => new Map([['camera', {}]])],
  ];

  it.each(hostile)('rejects %s with a SceneError, quickly', (_, make) => {
    const input = make();
    const start = performance.now();
    const error = thrown(() => parseScene(input));
    expect(performance.now() - start).toBeLessThan(1000);
    expect(error.issues.length).toBeGreaterThan(0);
  });

  it('names the array when there are too many spheres', () => {
    expect(issuesOf({ ...minimal(), spheres: Array(1e6).fill({}) })).toEqual([
      { path: 'spheres', message: `at most ${MAX_SPHERES} spheres` },
    ]);
  });
});

describe('parseSceneText', () => {
  const text = JSON.stringify(minimal());

  it('parses JSON text, with or without a byte order mark', () => {
    expect(parseSceneText(text)).toStrictEqual(parseScene(minimal()));
    expect(parseSceneText(`\ufeff${text}`)).toStrictEqual(parseScene(minimal()));
  });

  it.each([
    ['a missing brace', '{"camera": {"position": [0, 0, 1], "target": [0, 0, 0]}'],
    ['a trailing comma', '{"camera": 1,}'],
    ['an empty file', ''],
    ['single quotes', "{'camera': 1}"],
    ['a NaN literal', '{"camera": {"position": [NaN, 0, 1], "target": [0, 0, 0]}}'],
  ])('turns invalid JSON (%s) into a SceneError', (_, bad) => {
    const error = thrown(() => parseSceneText(bad));
    expect(error.issues).toEqual([{ path: '', message: expect.stringMatching(/^invalid JSON: ./) }]);
    expect(error.message).toMatch(/^scene: invalid JSON: /);
  });

  it('gives the line and column of a syntax error', () => {
    const error = thrown(() => parseSceneText('{\n  "camera": {,\n}'));
    expect(error.message).toMatch(/line 2/);
  });

  it('rejects text over MAX_SCENE_BYTES, counting UTF-8 bytes', () => {
    // Whitespace after the document is valid JSON, so only the size can fail.
    expect(() => parseSceneText(text.padEnd(MAX_SCENE_BYTES, ' '))).not.toThrow();
    const error = thrown(() => parseSceneText(text.padEnd(MAX_SCENE_BYTES + 1, ' ')));
    expect(error.issues).toEqual([{ path: '', message: `must be at most ${MAX_SCENE_BYTES} bytes of UTF-8 text` }]);
    // 400 000 three-byte characters are 1.2 MB although the string is shorter than the limit.
    const wide = `${text.slice(0, -1)}, "x": "${'\u20ac'.repeat(400_000)}"}`;
    expect(wide.length).toBeLessThan(MAX_SCENE_BYTES);
    expect(thrown(() => parseSceneText(wide)).message).toContain('bytes');
    expect(thrown(() => parseSceneText('x'.repeat(50_000_000))).message).toContain('bytes');
  });

  it('validates the parsed document', () => {
    expect(thrown(() => parseSceneText('{"camera": {"position": [0, 0, 1]}}')).message).toBe('camera.target: required');
    expect(thrown(() => parseSceneText('[1, 2, 3]')).message).toBe('scene: must be an object');
  });

  it('survives deeply nested JSON', () => {
    const deep = `${'['.repeat(400_000)}${']'.repeat(400_000)}`;
    expect(thrown(() => parseSceneText(deep)).issues).toHaveLength(1);
  });

  it('has a safe variant that returns the issues', () => {
    expect(safeParseSceneText('{')).toMatchObject({ ok: false });
    expect(safeParseSceneText(text)).toMatchObject({ ok: true });
    expect(safeParseSceneText(42 as unknown as string)).toMatchObject({ ok: false });
  });
});

describe('docs/scene-format.md', () => {
  const doc = readFileSync(join(__dirname, '../../docs/scene-format.md'), 'utf8');

  it('has only valid example scenes', () => {
    const examples = [...doc.matchAll(/```json\n([\s\S]*?)```/g)].map((match) => match[1]);
    expect(examples.length).toBeGreaterThanOrEqual(2);
    for (const example of examples) expect(() => parseSceneText(example)).not.toThrow();
  });

  it('documents every key', () => {
    const full = parseScene({ ...fixture('seed'), camera: { ...fixture('seed').camera, focusDistance: 5 } });
    const keys = new Set<string>();
    const collect = (value: unknown) => {
      if (typeof value !== 'object' || value === null) return;
      if (!Array.isArray(value)) Object.keys(value).forEach((key) => keys.add(key));
      Object.values(value).forEach(collect);
    };
    collect(serializeScene(full));
    expect(keys.size).toBeGreaterThan(20);
    for (const key of keys) expect(doc).toContain(`\`${key}\``);
  });

  it('shows error messages the parser really gives', () => {
    const block = /```\n(version: must be 1, 2 or 3[\s\S]*?)```/.exec(doc)?.[1];
    expect(block).toBeDefined();
    const input = edited((s) => {
      s.version = 4;
      s.camera.target = [...s.camera.position];
      s.image.width = 1.5;
      s.spheres[2].material.roughness = 3;
      s.spheres[4].material.color = '#12';
      s.lights[0].intensity = NaN;
      s.spheres[0].colour = [1, 0, 0];
      s.camera.focus_distance = 4;
    });
    const lines = thrown(() => parseScene(input)).message.split('\n');
    expect(lines.sort()).toEqual(block!.trim().split('\n').sort());
  });
});
