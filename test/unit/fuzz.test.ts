/**
 * Property tests of the scene parser: whatever it is given, it returns a
 * valid Scene or throws a SceneError with usable issues, and never anything
 * else. Accepted scenes are checked against an independent statement of the
 * rules and must round-trip through serializeScene.
 */
import { isTexture } from '../../src/scene/texture/texture';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { lightKindOf } from '../../src/lights/registry';
import {
  MAX_BOUNCES,
  MAX_IMAGE_SIZE,
  MAX_LIGHTS,
  MAX_SPHERES,
  SceneError,
  formatPath,
  parseScene,
  parseSceneText,
  safeParseScene,
  serializeScene,
  type Material,
  type Scene,
  type Vec3,
} from '../../src/scene';

const FIXTURES = join(__dirname, '../fixtures/scenes');
const fixtures: Record<string, unknown>[] = readdirSync(FIXTURES)
  .filter((file) => file.endsWith('.json'))
  .map((file) => JSON.parse(readFileSync(join(FIXTURES, file), 'utf8')));

type Path = (string | number)[];

// ---------------------------------------------------------------- checks

/** The property every input must satisfy. */
function checkParse(input: unknown): void {
  let scene: Scene;
  try {
    scene = parseScene(input);
  } catch (error) {
    expect(error, `parseScene threw something other than a SceneError: ${String(error)}`).toBeInstanceOf(SceneError);
    const { issues } = error as SceneError;
    expect(issues.length, 'a SceneError without issues').toBeGreaterThan(0);
    for (const issue of issues) {
      const what = `issue ${JSON.stringify(issue)}`;
      expect(typeof issue.path, `${what}: path is not a string`).toBe('string');
      expect(typeof issue.message, `${what}: message is not a string`).toBe('string');
      expect(issue.message.length, `${what}: empty message`).toBeGreaterThan(0);
      // The last-resort catch is for hostile objects (throwing getters), never for data like this.
      expect(issue.message, `${what}: the last-resort message for plain data`).not.toMatch(/^could not be read/);
    }
    return;
  }
  checkScene(scene);
  expect(parseScene(serializeScene(scene)), 'serialize then parse changed the scene').toStrictEqual(scene);
}

/** The rules of docs/scene-format.md, restated independently of the schema; each check says what failed. */
function checkScene(scene: Scene): void {
  const finite = (x: unknown) => typeof x === 'number' && Number.isFinite(x);
  const vec = (v: Vec3, ok: (x: number) => boolean = finite) =>
    Array.isArray(v) && v.length === 3 && v.every((x) => finite(x) && ok(x));
  const inBox = (x: number) => Math.abs(x) <= 1e6;
  const keys = (object: object, expected: string[], what: string) =>
    expect(Object.keys(object).sort(), `keys of ${what}`).toEqual(expected.sort());
  const check = (ok: boolean, what: string) => expect(ok, what).toBe(true);
  const material = (m: Material, what: string) => {
    const emission = m.emission ? ['emission'] : [];
    if (m.type === 'dielectric') {
      keys(m, ['type', 'color', 'roughness', 'ior', ...emission], what);
      check(m.ior >= 1.01 && m.ior <= 4, `${what}.ior in [1.01, 4]`);
    } else if (m.type === 'conductor') {
      keys(m, ['type', ...('metal' in m ? ['metal'] : []), 'eta', 'k', 'roughness', 'color', ...emission], what);
      check(vec(m.eta, (x) => x >= 0) && vec(m.k, (x) => x >= 0), `${what}.eta and k >= 0`);
    } else if (m.type === 'principled') {
      const scalars = ['metallic', 'roughness', 'specTint', 'specTrans', 'sheen', 'sheenTint', 'clearcoat', 'clearcoatGloss'] as const;
      keys(m, ['type', 'baseColor', ...scalars, 'ior', 'opacity', ...('normalMap' in m ? ['normalMap'] : []), ...emission], what);
      check(isTexture(m.baseColor) || vec(m.baseColor, (x) => x >= 0 && x <= 1), `${what}.baseColor in [0, 1]`);
      for (const key of [...scalars, 'opacity'] as const) {
        const v = m[key];
        check(isTexture(v) ? v.image.length > 0 : v >= 0 && v <= 1, `${what}.${key} in [0, 1] or a texture`);
      }
      check(m.ior >= 1.01 && m.ior <= 4, `${what}.ior in [1.01, 4]`);
    } else {
      keys(m, ['type', 'color', 'roughness', ...emission], what);
      check(m.type === 'standard', `${what}.type is standard or dielectric`);
    }
    if (m.type !== 'principled') check(vec(m.color, (x) => x >= 0 && x <= 1), `${what}.color in [0, 1]`);
    check(isTexture(m.roughness) || (m.roughness >= 0 && m.roughness <= 1), `${what}.roughness in [0, 1]`);
    if (m.emission) check(vec(m.emission.color, (x) => x >= 0) && m.emission.intensity >= 0, `${what}.emission >= 0`);
  };

  keys(scene, ['version', 'camera', 'image', 'render', 'environment', 'ground', 'lights', 'spheres', 'meshes'], 'the scene');
  check(scene.version === 1 || scene.version === 2 || scene.version === 3, 'version is 1, 2 or 3');
  const materials = [...scene.spheres.map((s) => s.material), ...scene.meshes.flatMap((m) => (m.material ? [m.material] : [])), ...(scene.ground ? [scene.ground.material] : [])];
  if (scene.meshes.some((m) => !m.material)) check(scene.version === 3, "meshes wear their files' materials only in version-3 documents");
  const v2Used = scene.meshes.length > 0 || (scene.environment !== null && 'map' in scene.environment) ||
    materials.some((m) => m.type !== 'standard' || m.emission);
  if (v2Used) check(scene.version >= 2, 'version-2 keys only in version-2 documents');
  if (materials.some((m) => m.type === 'conductor')) check(scene.version === 3, 'version-3 kinds only in version-3 documents');
  const { camera } = scene;
  check(vec(camera.position, inBox) && vec(camera.target, inBox) && vec(camera.up, inBox), 'camera vectors in the box');
  check(camera.position.some((x, i) => x !== camera.target[i]), 'camera.target differs from position');
  check(camera.up.some((x) => x !== 0), 'camera.up not zero');
  check(camera.fov > 0 && camera.fov < 180 && camera.aperture >= 0, 'camera.fov and aperture in range');
  if ('focusDistance' in camera) check(finite(camera.focusDistance) && camera.focusDistance! > 0, 'focusDistance > 0');
  const { width, height } = scene.image;
  for (const size of [width, height]) check(Number.isInteger(size) && size >= 1 && size <= MAX_IMAGE_SIZE, 'image size in range');
  const bounces = scene.render.maxBounces;
  check(Number.isInteger(bounces) && bounces >= 0 && bounces <= MAX_BOUNCES, 'maxBounces in range');
  const environment = scene.environment;
  if (environment !== null) {
    if ('map' in environment) {
      keys(environment, ['map', 'intensity', 'rotation'], 'environment');
      check(typeof environment.map === 'string' && environment.map.length > 0 && finite(environment.rotation), 'environment map and rotation');
    } else {
      keys(environment, ['color', 'intensity'], 'environment');
      check(vec(environment.color, (x) => x >= 0), 'environment.color >= 0');
    }
    check(finite(environment.intensity) && environment.intensity >= 0, 'environment.intensity >= 0');
  }
  if (scene.ground !== null) {
    check(finite(scene.ground.height), 'ground.height finite');
    material(scene.ground.material, 'ground.material');
    check(scene.ground.material.type !== 'dielectric' && !scene.ground.material.emission, 'ground has no inside, emits nothing');
  }
  check(scene.lights.length <= MAX_LIGHTS, 'at most MAX_LIGHTS lights');
  scene.lights.forEach((light, i) => {
    // Every key of its kind, explicit (beamWidth too: normalizing fills it in).
    keys(light, ['type', ...Object.keys(lightKindOf(light).shape)], `lights[${i}]`);
    const l = light as unknown as Record<string, number & Vec3>;
    check(vec(light.color, (x) => x >= 0) && (!('position' in l) || vec(l.position, inBox)), `lights[${i}] position and color`);
    check(!('radius' in l) || (l.radius > 0 && l.radius <= 1e6), `lights[${i}] radius`);
    for (const key of ['intensity', 'irradiance']) check(!(key in l) || (l[key] >= 0 && finite(l[key])), `lights[${i}].${key}`);
    if (light.type === 'spot') check(light.beamWidth >= 0 && light.beamWidth <= light.cutoffAngle && light.cutoffAngle <= 90, `lights[${i}] spot angles`);
    if (light.type === 'rectangle') check(light.size.every((x) => x > 0), `lights[${i}].size`);
  });
  check(scene.spheres.length <= MAX_SPHERES, 'at most MAX_SPHERES spheres');
  scene.spheres.forEach((sphere, i) => {
    keys(sphere, ['center', 'radius', 'material'], `spheres[${i}]`);
    check(vec(sphere.center, inBox) && sphere.radius > 0 && sphere.radius <= 1e6, `spheres[${i}] center and radius`);
    material(sphere.material, `spheres[${i}].material`);
  });
  scene.meshes.forEach((mesh, i) => {
    keys(mesh, ['file', 'material', 'position', 'rotation', 'scale'], `meshes[${i}]`);
    check(typeof mesh.file === 'string' && mesh.file.length > 0, `meshes[${i}].file`);
    check(vec(mesh.position, inBox) && vec(mesh.rotation) && vec(mesh.scale, (x) => x > 0), `meshes[${i}] transform`);
    if (mesh.material) material(mesh.material, `meshes[${i}].material`);
  });
}

// ---------------------------------------------------------------- tree editing

/** Big values shared between runs: never descended into, never modified. */
const SHARED = new Set<unknown>();

/** Every path to a value inside `value` (objects and arrays), root excluded; stays shallow and small. */
function pathsOf(value: unknown, prefix: Path = []): Path[] {
  if (typeof value !== 'object' || value === null || SHARED.has(value) || prefix.length > 8) return [];
  const entries: [string | number, unknown][] = Array.isArray(value)
    ? value.slice(0, 200).map((child, i) => [i, child])
    : Object.entries(value).slice(0, 200);
  return entries.flatMap(([key, child]) => [[...prefix, key], ...pathsOf(child, [...prefix, key])]);
}

function containerOf(root: unknown, path: Path): any {
  return path.slice(0, -1).reduce((node: any, key) => node[key], root);
}

// ---------------------------------------------------------------- hostile values

const HUGE_ARRAY: number[] = Array(1_000_000).fill(0);
const SPARSE_ARRAY: unknown[] = new Array(2 ** 32 - 1);
const LONG_STRING = '#'.padEnd(1_000_000, 'a');

function nested(depth: number, asObject: boolean): unknown {
  let value: unknown = 1;
  for (let i = 0; i < depth; i++) value = asObject ? { a: value } : [value];
  return value;
}
const DEEP_ARRAY = nested(100_000, false);
const DEEP_OBJECT = nested(100_000, true);
[HUGE_ARRAY, SPARSE_ARRAY, DEEP_ARRAY, DEEP_OBJECT].forEach((value) => SHARED.add(value));

const nastyValue: fc.Arbitrary<unknown> = fc.oneof(
  fc.constantFrom<unknown>(
    NaN, Infinity, -Infinity, 1e308, -1e308, 5e-324, -0, 0, 1, -1, 0.5, 1.5, 1 + 1e-9, -1e-9, 2 ** 53, 1e6, 1e6 + 1, 1e13, 8192, 8193, 64, 65, 180,
    null, undefined, true, false, '', '1', '#ffffff', '#FFF', 'red', [], {}, [0, 0, 0], [1, 1, 1], [NaN, 0, 0],
    [0, 0], [0, 0, 0, 0], HUGE_ARRAY, SPARSE_ARRAY, LONG_STRING, DEEP_ARRAY, DEEP_OBJECT,
  ),
  fc.double(),
  fc.integer(),
  fc.string({ maxLength: 20 }),
  fc.stringMatching(/^#[0-9a-gA-G]{0,7}$/),
  fc.array(fc.double(), { maxLength: 5 }),
  fc.anything({ maxDepth: 3 }),
  fc.integer({ min: 1, max: 3000 }).map((depth) => nested(depth, depth % 2 === 0)),
);

/** Numbers at and just beyond the edges of the documented ranges. */
const BOUNDARY_NUMBERS = [
  0, -0, 1, -1, 1 + 1e-9, -1e-9, 1.5, 5e-324, 64, 65, 179.999, 180, 8192, 8193,
  1e6, 1e6 + 1, -1e6, -1e6 - 1, 1e12, 1e13, 1e308, NaN, Infinity, -Infinity,
];

type Mutation =
  | { kind: 'set'; at: number; value: unknown }
  | { kind: 'delete'; at: number }
  | { kind: 'add'; at: number; key: string; value: unknown }
  | { kind: 'wrap'; at: number };

const mutation: fc.Arbitrary<Mutation> = fc.oneof(
  { arbitrary: fc.record({ kind: fc.constant('set' as const), at: fc.nat(), value: nastyValue }), weight: 2 },
  {
    arbitrary: fc.record({ kind: fc.constant('set' as const), at: fc.nat(), value: fc.constantFrom(...BOUNDARY_NUMBERS) }),
    weight: 3,
  },
  fc.record({ kind: fc.constant('delete' as const), at: fc.nat() }),
  fc.record({
    kind: fc.constant('add' as const),
    at: fc.nat(),
    key: fc.oneof(fc.string({ maxLength: 12 }), fc.constantFrom('colour', 'raduis', '__proto__', 'constructor', 'color')),
    value: nastyValue,
  }),
  fc.record({ kind: fc.constant('wrap' as const), at: fc.nat() }),
);

/** Applies `m` at one of the value's paths (the root included, as index 0). */
function mutate(root: { value: unknown }, m: Mutation): void {
  let paths: Path[] = [[], ...pathsOf(root.value)].map((path) => ['value', ...path]);
  if (m.kind === 'set' && typeof m.value === 'number') {
    // Aim numbers at numbers, where the range checks are.
    const numbers = paths.filter((path) => typeof containerOf(root, path)[path[path.length - 1]] === 'number');
    if (numbers.length > 0) paths = numbers;
  }
  const path = paths[m.at % paths.length];
  const parent = containerOf(root, path);
  const key = path[path.length - 1];
  switch (m.kind) {
    case 'set':
      parent[key] = m.value;
      break;
    case 'delete':
      if (Array.isArray(parent)) parent.splice(Number(key), 1);
      else delete parent[key];
      break;
    case 'add': {
      const target = parent[key];
      if (SHARED.has(target)) parent[key] = m.value;
      else if (Array.isArray(target)) target.push(m.value);
      else if (typeof target === 'object' && target !== null) Object.defineProperty(target, m.key, { value: m.value, enumerable: true, configurable: true, writable: true });
      else parent[key] = m.value;
      break;
    }
    case 'wrap':
      parent[key] = Array.isArray(parent[key]) ? { value: parent[key] } : [parent[key]];
      break;
  }
}

// ---------------------------------------------------------------- valid scenes

const coordinate = fc.double({ min: -1e6, max: 1e6, noNaN: true });
const point = fc.tuple(coordinate, coordinate, coordinate);
const unit = fc.double({ min: 0, max: 1, noNaN: true });
const hex = fc
  .tuple(fc.nat(255), fc.nat(255), fc.nat(255), fc.boolean())
  .map(([r, g, b, upper]) => {
    const text = `#${[r, g, b].map((c) => c.toString(16).padStart(2, '0')).join('')}`;
    return upper ? text.toUpperCase() : text;
  });
const albedo = fc.oneof(fc.tuple(unit, unit, unit), hex);
const emission = fc.oneof(fc.tuple(fc.double({ min: 0, max: 1e3, noNaN: true }), unit, unit), hex);
const positive = fc.double({ min: 1e-6, max: 1e6, noNaN: true });
const material = fc.record({ color: albedo, roughness: unit }, { requiredKeys: [] });

const validScene = fc.record(
  {
    version: fc.constant(1),
    camera: fc.record(
      {
        position: point,
        target: point,
        up: point.filter((v) => Math.hypot(...v) >= 1e-3),
        fov: fc.double({ min: 0.01, max: 179.99, noNaN: true }),
        aperture: fc.double({ min: 0, max: 10, noNaN: true }),
        focusDistance: positive,
      },
      { requiredKeys: ['position', 'target'] },
    ).filter((c) => Math.hypot(c.position[0] - c.target[0], c.position[1] - c.target[1], c.position[2] - c.target[2]) >= 1e-3),
    image: fc.record({ width: fc.integer({ min: 1, max: MAX_IMAGE_SIZE }), height: fc.integer({ min: 1, max: MAX_IMAGE_SIZE }) }),
    render: fc.record({ maxBounces: fc.integer({ min: 0, max: MAX_BOUNCES }) }, { requiredKeys: [] }),
    environment: fc.option(fc.record({ color: emission, intensity: fc.double({ min: 0, max: 1e6, noNaN: true }) }, { requiredKeys: [] })),
    ground: fc.option(fc.record({ height: coordinate, material }, { requiredKeys: [] })),
    lights: fc.array(
      fc.record({ position: point, radius: positive, color: emission, intensity: fc.double({ min: 0, max: 1e6, noNaN: true }) }, { requiredKeys: ['position', 'radius'] }),
      { maxLength: MAX_LIGHTS },
    ),
    spheres: fc.array(fc.record({ center: point, radius: positive, material }, { requiredKeys: ['center', 'radius'] }), { maxLength: 20 }),
  },
  { requiredKeys: ['camera'] },
);

/** Version 3: a textured principled ground (every texture key, each optional). */
const angle = fc.double({ min: -1e6, max: 1e6, noNaN: true });
const uvTransform = fc.record({ offset: fc.tuple(angle, angle), scale: fc.tuple(angle, angle), rotation: angle }, { requiredKeys: [] });
const imageName = fc.constantFrom('a.png', 'dir/b.jpg', 'c d.webp', 'e.exr');
const scalarTexture = fc.record(
  { image: imageName, channel: fc.constantFrom('r', 'g', 'b', 'a'), scale: fc.double({ min: 0, max: 1e6, noNaN: true }), uv: uvTransform, cutoff: unit },
  { requiredKeys: ['image'] },
);
const colorTexture = fc.record({ image: imageName, scale: fc.oneof(fc.double({ min: 0, max: 1e6, noNaN: true }), fc.tuple(unit, unit, unit)), uv: uvTransform }, { requiredKeys: ['image'] });
const texturedGround = fc.record({
  version: fc.constant(3),
  camera: fc.constant({ position: [0, 1, 5], target: [0, 0, 0] }),
  ground: fc.record({
    material: fc.record(
      {
        type: fc.constant('principled'),
        baseColor: fc.oneof(albedo, colorTexture),
        metallic: fc.oneof(unit, scalarTexture),
        roughness: fc.oneof(unit, scalarTexture),
        clearcoat: fc.oneof(unit, scalarTexture),
        opacity: fc.oneof(unit, scalarTexture),
        normalMap: fc.record({ image: imageName, scale: angle, uv: uvTransform }, { requiredKeys: ['image'] }),
      },
      { requiredKeys: ['type'] },
    ),
  }),
});

// ---------------------------------------------------------------- properties

describe('fuzzing parseScene', () => {
  it('accepts and round-trips generated valid scenes', () => {
    fc.assert(
      fc.property(validScene, (json) => {
        const result = safeParseScene(json);
        if (!result.ok) throw new Error(`rejected a valid scene: ${JSON.stringify(result.issues)}`);
        checkScene(result.scene);
        expect(parseScene(serializeScene(result.scene)), 'serialize then parse changed the scene').toStrictEqual(result.scene);
        expect(parseSceneText(JSON.stringify(serializeScene(result.scene))), 'serialize, stringify, parse text changed the scene').toStrictEqual(result.scene);
      }),
      { numRuns: 1000 },
    );
  });

  it('accepts and round-trips generated textured scenes (version 3)', () => {
    fc.assert(
      fc.property(texturedGround, (json) => {
        const result = safeParseScene(json);
        if (!result.ok) throw new Error(`rejected a valid scene: ${JSON.stringify(result.issues)}`);
        checkScene(result.scene);
        expect(parseScene(serializeScene(result.scene))).toStrictEqual(result.scene);
      }),
      { numRuns: 300 },
    );
  });

  it('returns a valid Scene or throws a SceneError for mutated fixtures', () => {
    fc.assert(
      fc.property(fc.constantFrom(...fixtures), fc.array(mutation, { minLength: 1, maxLength: 4 }), (fixture, mutations) => {
        const root = { value: structuredClone(fixture) as unknown };
        for (const m of mutations) mutate(root, m);
        checkParse(root.value);
      }),
      { numRuns: 3000 },
    );
  });

  it('returns a valid Scene or throws a SceneError for arbitrary values', () => {
    fc.assert(fc.property(fc.oneof(fc.anything(), nastyValue), checkParse), { numRuns: 1000 });
  });

  it('throws only SceneError for arbitrary text', () => {
    const text = fc.oneof(
      fc.string(),
      fc.json(),
      fc.constantFrom(...fixtures).chain((f) => {
        const json = JSON.stringify(f);
        return fc.tuple(fc.nat(json.length), fc.nat(json.length), fc.string({ maxLength: 5 })).map(
          ([from, to, insert]) => json.slice(0, Math.min(from, to)) + insert + json.slice(Math.max(from, to)),
        );
      }),
    );
    fc.assert(
      fc.property(text, (input) => {
        try {
          checkScene(parseSceneText(input));
        } catch (error) {
          if (!(error instanceof SceneError)) throw error;
          expect(error.issues.length, 'a SceneError without issues').toBeGreaterThan(0);
        }
      }),
      { numRuns: 1000 },
    );
  });
});

describe('every bad value is reported at its own path', () => {
  const seed = fixtures.find((f) => ((f.spheres ?? []) as unknown[]).length === 5 && (f.version ?? 1) === 1)!;
  const leaves = pathsOf(seed).filter((path) => typeof containerOf(seed, path)[path[path.length - 1]] === 'number');

  it.each([
    ['NaN', NaN],
    ['Infinity', -Infinity],
    ['a string', 'x'],
    ['null', null],
    ['an object', {}],
  ])('%s at any number', (_, value) => {
    expect(leaves.length, 'numbers found in the seed fixture').toBeGreaterThan(50);
    for (const path of leaves) {
      const copy = structuredClone(seed);
      containerOf(copy, path)[path[path.length - 1]] = value;
      const result = safeParseScene(copy);
      expect(result.ok ? [] : result.issues.map((issue) => issue.path), `${JSON.stringify(value)} at ${formatPath(path)}`).toEqual([formatPath(path)]);
    }
  });

  it('a boundary number at any number is accepted only where the rules allow it', () => {
    for (const path of leaves) {
      for (const value of BOUNDARY_NUMBERS) {
        const copy = structuredClone(seed);
        containerOf(copy, path)[path[path.length - 1]] = value;
        const result = safeParseScene(copy);
        if (result.ok) checkScene(result.scene);
        else expect(result.issues.map((issue) => issue.path), `${value} at ${formatPath(path)}`).toEqual([formatPath(path)]);
      }
    }
  });

  it('an unknown key in any object', () => {
    const objects = [[], ...pathsOf(seed)].filter((path) => {
      const value = path.reduce((node: any, key) => node[key], seed);
      return typeof value === 'object' && value !== null && !Array.isArray(value);
    });
    expect(objects.length, 'objects found in the seed fixture').toBeGreaterThan(10);
    for (const path of objects) {
      const copy: any = structuredClone(seed);
      path.reduce((node: any, key) => node[key], copy).zz = 1;
      const result = safeParseScene(copy);
      expect(result.ok ? [] : result.issues, `unknown key zz in ${formatPath(path) || 'the root'}`).toEqual([{ path: formatPath([...path, 'zz']), message: 'unknown key' }]);
    }
  });
});
