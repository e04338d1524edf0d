/**
 * Model scenes (src/scene/modelScene.ts, src/cli/model.ts): the fit and the
 * framing the page and the command line share, glTF cameras read from the
 * JSON (node hierarchy, TRS and matrices, .gltf and .glb) and carried
 * through the mesh's placement, the scene document, and `pathtrace scene` /
 * `pathtrace render MODEL` with a fake session: the model's scene and the
 * printed scene file load the same scene; bad models and flags are one line,
 * exit 2.
 */
import { mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterEach, beforeEach, describe, expect, it } from 'vitest';
import { bundledMapBytes } from '../../src/app/bundledMaps';
import { fitMesh } from '../../src/app/meshFit';
import { run } from '../../src/cli/main';
import { MODEL_EXTENSIONS } from '../../src/cli/model';
import type { CliSession, SessionModule } from '../../src/cli/render';
import { cameraRay } from '../../src/scene/camera';
import { decodeMesh, MESH_EXTENSIONS, transformMesh } from '../../src/scene/mesh';
import { readGltfCameras } from '../../src/scene/mesh/gltfCameras';
import { fitMeshToView, frameCamera, gltfCameraInScene, modelSceneDocument, STUDIO_MAP, worldBoundingSphere } from '../../src/scene/modelScene';
import { intersectMesh } from '../../src/scene/picking';
import { defaultScene } from '../../src/scene/presets';
import { parseScene } from '../../src/scene/schema';
import type { Camera, Scene, TriangleMesh, Vec3 } from '../../src/scene/types';
import { icosphere } from '../support/icosphere';

const MESHES = new URL('../fixtures/meshes/', import.meta.url).pathname;
const FIXTURE_SCENES = new URL('../fixtures/scenes/', import.meta.url).pathname;
const ico = icosphere(1, true);
/** The icosphere stretched and moved off the origin: 2 x 1 x 0.5, centred at (3, 4, 5). */
const box: TriangleMesh = { ...ico, positions: ico.positions.map((p, i) => [p * 1, p * 0.5, p * 0.25][i % 3] + [3, 4, 5][i % 3]) };

function worldBounds(data: TriangleMesh, fit: { position: Vec3; rotation: Vec3; scale: Vec3 }) {
  const world = transformMesh(data, fit);
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < world.positions.length; i++) {
    min[i % 3] = Math.min(min[i % 3], world.positions[i]);
    max[i % 3] = Math.max(max[i % 3], world.positions[i]);
  }
  return { min, max, world };
}

/** Where a world point lands in the image, (u, v) in [0, 1] with v down; null behind the camera. */
function project(camera: Camera, aspect: number, p: Vec3): { u: number; v: number } | null {
  const f = camera.target.map((t, k) => t - camera.position[k]);
  const fl = Math.hypot(...f);
  const fw = f.map((x) => x / fl);
  const r = [fw[1] * camera.up[2] - fw[2] * camera.up[1], fw[2] * camera.up[0] - fw[0] * camera.up[2], fw[0] * camera.up[1] - fw[1] * camera.up[0]];
  const rl = Math.hypot(...r);
  const right = r.map((x) => x / rl);
  const up = [right[1] * fw[2] - right[2] * fw[1], right[2] * fw[0] - right[0] * fw[2], right[0] * fw[1] - right[1] * fw[0]];
  const d = p.map((x, k) => x - camera.position[k]);
  const dot = (a: number[], b: number[]) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const z = dot(d, fw);
  if (z <= 0) return null;
  const t = Math.tan((camera.fov * Math.PI) / 360);
  return { u: 0.5 + dot(d, right) / (z * t * aspect * 2), v: 0.5 - dot(d, up) / (z * t * 2) };
}

describe('fitting and framing a model (shared by the page and the CLI)', () => {
  it('the page fits to its scene with the shared code: on its ground, or centred on the target without one', () => {
    const scene = defaultScene();
    expect(fitMesh(box, 'box.ply', scene)).toEqual(fitMeshToView(box, 'box.ply', scene.camera, scene.ground!.height));
    const floating = fitMesh(box, 'box.ply', { ...scene, ground: null });
    const { min, max } = worldBounds(box, floating);
    expect((min[1] + max[1]) / 2).toBeCloseTo(scene.camera.target[1], 6);
  });

  it('stands the model on the ground under the target, its largest side 0.3 of the view distance', () => {
    const camera = { position: [1, 3, 9] as Vec3, target: [1, 1, -1] as Vec3 };
    const fit = fitMeshToView(box, 'box.glb', camera, -0.5);
    const { min, max } = worldBounds(box, fit);
    expect(min[1]).toBeCloseTo(-0.5, 6);
    expect((min[0] + max[0]) / 2).toBeCloseTo(1, 6);
    expect((min[2] + max[2]) / 2).toBeCloseTo(-1, 6);
    expect(Math.max(...max.map((m, k) => m - min[k])) / Math.hypot(0, 2, 10)).toBeCloseTo(0.3, 6);
  });

  it('frames the model: every vertex inside the image, at several aspects', () => {
    const scene = defaultScene();
    const fit = fitMeshToView(box, 'box.glb', scene.camera, 0);
    const { world } = worldBounds(box, fit);
    const sphere = worldBoundingSphere(fit, box);
    for (const aspect of [0.5, 1, 16 / 9, 3]) {
      const camera = frameCamera(scene.camera, sphere.center, sphere.radius, aspect);
      for (let i = 0; i < world.positions.length; i += 3) {
        const p = project(camera, aspect, [world.positions[i], world.positions[i + 1], world.positions[i + 2]])!;
        expect(p.u).toBeGreaterThan(0);
        expect(p.u).toBeLessThan(1);
        expect(p.v).toBeGreaterThan(0);
        expect(p.v).toBeLessThan(1);
      }
    }
  });
});

describe('the model scene document', () => {
  const image = { width: 96, height: 60 };

  it('version 3, the mesh without a material, on a grey ground, lit by the map, framed by the default camera', () => {
    const doc = modelSceneDocument({ file: 'models/box.glb', data: box, image, environmentMap: STUDIO_MAP, environmentIntensity: 0.2 });
    expect(doc.version).toBe(3);
    const meshes = doc.meshes as Record<string, unknown>[];
    expect(meshes).toHaveLength(1);
    expect(meshes[0]).not.toHaveProperty('material');
    expect(meshes[0].file).toBe('models/box.glb');
    expect(doc.environment).toEqual({ map: STUDIO_MAP, intensity: 0.2, rotation: 0 });
    expect(doc.lights).toEqual([]);
    const scene = parseScene(doc);
    expect(scene.ground?.material).toMatchObject({ color: [0.5, 0.5, 0.5], roughness: 1 });
    expect(scene.image).toEqual(image);
    // The centre ray hits the placed model.
    expect(intersectMesh(cameraRay(scene.camera, 96 / 60, 0.5, 0.5), scene.meshes[0], box)).not.toBeNull();
  });

  it('without a map: a uniform white sky', () => {
    const scene = parseScene(modelSceneDocument({ file: 'box.obj', data: box, image, environmentMap: null }));
    expect(scene.environment).toEqual({ color: [1, 1, 1], intensity: 0.8 });
  });
});

/** A glTF JSON with camera 0 under a translated, rotated parent, camera 1 by matrix, camera 2 orthographic and unplaced. */
function cameraGltf(): Record<string, unknown> {
  const half = Math.SQRT1_2;
  return {
    asset: { version: '2.0' },
    scene: 1,
    scenes: [{ nodes: [] }, { nodes: [0, 3] }],
    nodes: [
      // Parent: 90 degrees about +y, then moved to (10, 0, 0); scale 2.
      { translation: [10, 0, 0], rotation: [0, half, 0, half], scale: [2, 2, 2], children: [1, 2] },
      { translation: [0, 1, 3], camera: 0 },
      { camera: 0 }, // a second node with camera 0: the first one (depth first) places it
      { matrix: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 5, 1], camera: 1 },
    ],
    cameras: [
      { type: 'perspective', name: 'main', perspective: { yfov: 0.5, aspectRatio: 1.5, znear: 0.1 } },
      { type: 'perspective', perspective: { yfov: 1, znear: 0.1 } },
      { type: 'orthographic', orthographic: { xmag: 1, ymag: 1, znear: 0, zfar: 1 } },
    ],
  };
}

function glb(json: unknown): Uint8Array {
  let text = JSON.stringify(json);
  while (text.length % 4 !== 0) text += ' ';
  const body = new TextEncoder().encode(text);
  const out = new Uint8Array(20 + body.length);
  const view = new DataView(out.buffer);
  view.setUint32(0, 0x46546c67, true);
  view.setUint32(4, 2, true);
  view.setUint32(8, out.length, true);
  view.setUint32(12, body.length, true);
  view.setUint32(16, 0x4e4f534a, true);
  out.set(body, 20);
  return out;
}

const apply = (m: ArrayLike<number>, v: number[]) => [0, 1, 2].map((r) => m[r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2] + m[12 + r] * v[3]);

describe('glTF cameras', () => {
  it('reads each camera with the world transform of the first node of the default scene naming it', () => {
    const text = new TextEncoder().encode(JSON.stringify(cameraGltf()));
    for (const [bytes, binary] of [[text, false], [glb(cameraGltf()), true]] as const) {
      const cameras = readGltfCameras(bytes, binary);
      expect(cameras.map((c) => [c.index, c.name, c.type, c.yfov])).toEqual([[0, 'main', 'perspective', 0.5], [1, '', 'perspective', 1], [2, '', 'orthographic', undefined]]);
      expect(cameras[0].aspectRatio).toBe(1.5);
      // Child at (0, 1, 3) under "rotate +90 about y, scale 2, move to x = 10": (0, 2, 6) rotated -> (6, 2, 0), + (10, 0, 0).
      const p = apply(cameras[0].world!, [0, 0, 0, 1]);
      [16, 2, 0].forEach((x, k) => expect(p[k]).toBeCloseTo(x, 12));
      // Its -z looks along -x after the rotation (x2: the scale).
      const d = apply(cameras[0].world!, [0, 0, -1, 0]);
      [-2, 0, 0].forEach((x, k) => expect(d[k]).toBeCloseTo(x, 12));
      expect(apply(cameras[1].world!, [0, 0, 0, 1])).toEqual([0, 0, 5]);
      expect(cameras[2].world).toBeNull();
    }
  });

  it('a file without cameras has none; broken files are errors that say so', () => {
    expect(readGltfCameras(readFileSync(join(MESHES, 'bench.glb')), true)).toEqual([]);
    expect(() => readGltfCameras(new Uint8Array([1, 2, 3]), true)).toThrow(/not a glTF binary file/);
    expect(() => readGltfCameras(new TextEncoder().encode('{"asset":'), false)).toThrow(/glTF JSON is invalid/);
  });

  it('goes through the mesh placement: position, view direction and fov in degrees', () => {
    const [camera] = readGltfCameras(glb(cameraGltf()), true);
    const fit = { position: [1, 2, 3] as Vec3, rotation: [0, 90, 0] as Vec3, scale: [0.5, 0.5, 0.5] as Vec3 };
    const placed = gltfCameraInScene(camera, fit, [0, 0, 0]);
    // The camera's file position (16, 2, 0), scaled by 0.5 -> (8, 1, 0), rotated 90 about y -> (0, 1, -8), moved.
    [1, 3, -5].forEach((x, k) => expect(placed.position[k]).toBeCloseTo(x, 9));
    // File direction -x, rotated 90 about y -> +z.
    const dir = placed.target.map((t, k) => t - placed.position[k]);
    const length = Math.hypot(...dir);
    [0, 0, 1].forEach((x, k) => expect(dir[k] / length).toBeCloseTo(x, 9));
    [0, 1, 0].forEach((x, k) => expect(placed.up[k]).toBeCloseTo(x, 9));
    expect(placed.fov).toBeCloseTo((0.5 * 180) / Math.PI, 12);
    // The target is the point of the axis nearest the model's centre.
    expect(length).toBeCloseTo(5, 9);
  });
});

interface Loaded {
  scene: Scene;
  options: { width: number; height: number; seed: number };
}

/** A session that records what it is asked to load and renders a flat grey. */
function fakeSession(loads: Loaded[]): SessionModule {
  return {
    TONEMAPS: ['none'],
    async openRenderSession() {
      let size = { width: 0, height: 0 };
      const session: CliSession = {
        async load(scene, options) {
          loads.push({ scene, options });
          size = options;
          return { renderer: 'fake' };
        },
        async render(n) {
          return n;
        },
        async readLinear() {
          return new Float32Array(size.width * size.height * 4).fill(0.5);
        },
        async readDisplayed() {
          return new Uint8Array(size.width * size.height * 4).fill(128);
        },
        async close() {},
      };
      return session;
    },
  };
}

describe('pathtrace scene / render MODEL (fake session)', () => {
  let dir: string;
  beforeEach(() => {
    dir = mkdtempSync(join(tmpdir(), 'pathtrace-model-'));
  });
  afterEach(() => rmSync(dir, { recursive: true, force: true }));

  const capture = () => ({ text: '', isTTY: false, write(chunk: string) { this.text += chunk; return true; } });
  async function cli(argv: string[], loads: Loaded[] = []) {
    const stdout = capture();
    const stderr = capture();
    const code = await run(argv, { stdout, stderr, cwd: dir, env: {}, now: () => 0, loadSession: async () => fakeSession(loads) });
    return { code, stdout: stdout.text, stderr: stderr.text };
  }

  it('decodeMesh and the CLI know the same model extensions', () => {
    expect([...MODEL_EXTENSIONS].sort()).toEqual([...MESH_EXTENSIONS].sort());
  });

  it('prints a version-3 scene naming the model relative to the current directory (or to -o), without a material', async () => {
    const model = join(MESHES, 'bench.glb');
    const printed = await cli(['scene', model, '--width', '96', '--height', '60']);
    expect(printed.stderr).toBe('');
    expect(printed.code).toBe(0);
    const json = JSON.parse(printed.stdout);
    expect(json.version).toBe(3);
    expect(json.meshes).toHaveLength(1);
    expect(json.meshes[0]).not.toHaveProperty('material');
    expect(join(dir, json.meshes[0].file)).toBe(model);
    expect(json.environment).toEqual({ map: 'bundled/studio.exr', intensity: 0.2, rotation: 0 });
    expect(json.image).toEqual({ width: 96, height: 60 });

    writeFileSync(join(dir, 'sky.hdr'), readFileSync(new URL('../fixtures/envmaps/gradient-rle.hdr', import.meta.url)));
    const written = await cli(['scene', model, '-o', join(dir, 'sub-scene.json'), '--env', join(dir, 'sky.hdr')]);
    expect(written.code).toBe(0);
    const file = JSON.parse(readFileSync(join(dir, 'sub-scene.json'), 'utf8'));
    expect(file.environment).toEqual({ map: 'sky.hdr', intensity: 1, rotation: 0 });
    expect(file.image).toEqual({ width: 640, height: 480 });

    const none = JSON.parse((await cli(['scene', model, '--env', 'none'])).stdout);
    expect(none.environment).toEqual({ color: [1, 1, 1], intensity: 0.8 });
  });

  it('render MODEL loads exactly the scene that rendering the printed scene file loads', async () => {
    const model = join(MESHES, 'ico-smooth.obj');
    const printed = await cli(['scene', model, '--height', '50']);
    writeFileSync(join(dir, 'printed.json'), printed.stdout);
    const loads: Loaded[] = [];
    const options = ['--spp', '2', '--seed', '7'];
    const fromModel = await cli(['render', model, ...options, '--height', '50'], loads);
    expect(fromModel.code).toBe(0);
    expect(fromModel.stderr).toMatch(/rendered 67x50 at 2 spp .* -> .*ico-smooth\.png/);
    const fromFile = await cli(['render', join(dir, 'printed.json'), ...options, '-o', join(dir, 'b.png')], loads);
    expect(fromFile.code).toBe(0);
    expect(loads).toHaveLength(2);
    expect(loads[0]).toEqual(loads[1]);
    expect(loads[0].scene.environment).toMatchObject({ map: 'bundled/studio.exr' });
  });

  it('a bundled map not beside the scene comes from the bundle (validate, export-mitsuba copies it beside the XML); a file beside it wins', async () => {
    const sceneFile = join(dir, 'bench-scene.json');
    expect((await cli(['scene', join(MESHES, 'bench.glb'), '-o', sceneFile])).code).toBe(0);
    const valid = await cli(['validate', sceneFile]);
    expect(valid.stdout).toMatch(/valid scene .*environment map bundled\/studio\.exr/);
    expect(valid.code).toBe(0);

    const exported = await cli(['export-mitsuba', sceneFile, '-o', join(dir, 'out.xml')]);
    expect(exported.code, exported.stderr).toBe(0);
    const copy = readFileSync(join(dir, 'out-studio.exr'));
    expect(copy.equals(Buffer.from(await bundledMapBytes('studio')))).toBe(true);
    expect(readFileSync(join(dir, 'out.xml'), 'utf8')).toContain(join(dir, 'out-studio.exr'));

    mkdirSync(join(dir, 'bundled'));
    writeFileSync(join(dir, 'bundled/studio.exr'), 'not a map');
    const shadowed = await cli(['validate', sceneFile]);
    expect(shadowed.code).toBe(2);
    expect(shadowed.stderr).toMatch(/^environment\.map: "bundled\/studio\.exr": /);
  });

  it('a missing, corrupt or unsupported model, or a bad --camera / --env, is one line naming it, exit 2, before any session', async () => {
    const corrupt = join(dir, 'broken.glb');
    writeFileSync(corrupt, readFileSync(join(MESHES, 'bench.glb')).subarray(0, 400));
    const notGltf = join(MESHES, 'ico-flat.obj');
    const cases: [string[], RegExp][] = [
      [['render', join(dir, 'gone.glb')], /^.*gone\.glb: cannot read model: no such file$/],
      [['scene', join(dir, 'gone.ply')], /^.*gone\.ply: cannot read model: no such file$/],
      [['render', corrupt], /^.*broken\.glb: .+$/],
      [['scene', join(dir, 'x.stl')], /^.*x\.stl: not a model file \(use \.obj, \.ply, \.gltf, \.glb\)$/],
      [['render', join(MESHES, 'bench.glb'), '--camera'], /^--camera: .*bench\.glb has no cameras$/],
      [['render', notGltf, '--camera', '1'], /^--camera: .*ico-flat\.obj is not a glTF file; only glTF files carry cameras$/],
      [['scene', join(MESHES, 'bench.glb'), '--env', join(dir, 'nothing.hdr')], /^--env: "nothing\.hdr": cannot be read/],
      [['render', join(FIXTURE_SCENES, 'seed.json'), '--env', 'none'], /^--env: only for a model file/],
    ];
    for (const [argv, line] of cases) {
      const loads: Loaded[] = [];
      const result = await cli(argv, loads);
      expect(result.code, argv.join(' ')).toBe(2);
      const lines = result.stderr.trim().split('\n');
      expect(lines, argv.join(' ')).toHaveLength(1);
      expect(lines[0], argv.join(' ')).toMatch(line);
      expect(loads).toHaveLength(0);
    }
  });

  it('--camera N looks through the file camera, placed with the model', async () => {
    // The icosphere with a camera 4 units in front of it (+z), looking at it.
    const gltfText = readFileSync(join(MESHES, 'ico-smooth.gltf'), 'utf8');
    const gltf = JSON.parse(gltfText);
    const root = gltf.scenes[gltf.scene ?? 0].nodes as number[];
    gltf.nodes.push({ translation: [0, 0, 4], camera: 0 });
    root.push(gltf.nodes.length - 1);
    gltf.cameras = [{ type: 'perspective', perspective: { yfov: 0.6, znear: 0.01 } }];
    writeFileSync(join(dir, 'seen.gltf'), JSON.stringify(gltf));
    for (const buffer of gltf.buffers ?? []) {
      if (buffer.uri && !buffer.uri.startsWith('data:')) writeFileSync(join(dir, buffer.uri), readFileSync(join(MESHES, buffer.uri)));
    }
    const result = await cli(['scene', join(dir, 'seen.gltf'), '--camera', '0', '--width', '80', '--height', '80']);
    expect(result.stderr).toBe('');
    const scene = parseScene(JSON.parse(result.stdout));
    expect(scene.camera.fov).toBeCloseTo((0.6 * 180) / Math.PI, 9);
    const [s] = scene.meshes[0].scale;
    // 4 file units in front of the model's centre, in scene units: 4 * scale, looking at it.
    const data = await decodeMesh(readFileSync(join(dir, 'seen.gltf')), 'seen.gltf');
    const center = worldBoundingSphere(scene.meshes[0], data).center;
    expect(Math.hypot(...scene.camera.position.map((p, k) => p - center[k]))).toBeCloseTo(4 * s, 5);
    expect(intersectMesh(cameraRay(scene.camera, 1, 0.5, 0.5), scene.meshes[0], data)).not.toBeNull();
    const wrong = await cli(['scene', join(dir, 'seen.gltf'), '--camera', '3']);
    expect(wrong.stderr.trim()).toMatch(/^--camera: .*seen\.gltf has 1 camera \(0 to 0\) \(got 3\)$/);
  });
});
