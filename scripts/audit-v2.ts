/**
 * Bias audit on version-2 scenes the shared fixtures do not cover: each scene
 * below is rendered by Mitsuba 3 through the project's own exporter (exactly
 * as scripts/make-reference.sh makes references: `pathtrace export-mitsuba`,
 * then bench/mitsuba/render.py, scalar_rgb) and by our renderer (the page the
 * CLI drives, through the same RenderSession, in BATCHES independent seeds),
 * and compared block by block with the noise measured from the batches, as
 * test/browser/references.test.ts does.
 *
 *   npx tsx scripts/audit-v2.ts [--only NAME[,NAME]] [--ref-spp 4096] [--spp 512]
 *
 * Needs `npm run build` (CLI + page) and Mitsuba 3 (`python3 -c "import mitsuba"`).
 * Scenes, meshes, maps and the references go to $AUDIT_DIR (default
 * /tmp/audit-v2); a reference is reused when its scene JSON and spp are unchanged.
 * Prints one line per scene and flags any scene with a block off by more than
 * Z_FLAG sigma or REL_FLAG relative error beyond 2 sigma of noise.
 * Writes ours/reference PFMs beside the scene for inspection.
 */
import { execFileSync } from 'node:child_process';
import { copyFileSync, existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { decodePfm, encodePfm } from '../src/image/pfm';
import { average, blockMeans, meanValue, predictedRelMse, relativeMse, varianceOfMean, type LinearImage } from '../src/node/imageMetrics';
import { openRenderSession } from '../src/node/session';
import { readSceneFiles } from '../src/node/sceneFiles';
import { parseSceneText } from '../src/scene/schema';

const ROOT = fileURLToPath(new URL('..', import.meta.url));
const FIXTURES = path.join(ROOT, 'test/fixtures');
const BLOCK = 16;
const BATCHES = 8;
const Z_FLAG = 6;
const REL_FLAG = 0.03;

/** An open unit quad in the xy plane, counter-clockwise seen from +z (flat: normal +z). */
const QUAD_OBJ = `# unit quad, normal +z
v -0.5 -0.5 0
v 0.5 -0.5 0
v 0.5 0.5 0
v -0.5 0.5 0
f 1 2 3
f 1 3 4
`;

type Json = Record<string, unknown>;
interface AuditScene {
  scene: Json;
  /** Our total spp (split into BATCHES seeds). */
  spp?: number;
  refSpp?: number;
  note: string;
}

const groundRough = { height: 0, material: { color: [0.6, 0.6, 0.6], roughness: 0.7 } };

const SCENES: Record<string, AuditScene> = {
  'mesh-transform': {
    note: 'flat OBJ, rotation [30,45,60], scale [1.4,0.6,0.9]; smooth PLY rotation [-20,110,35], scale [0.5,0.9,0.7]; r 0.3 / 1 standard',
    scene: {
      version: 2,
      camera: { position: [0, 1.6, 4.5], target: [0, 0.6, 0], fov: 40 },
      image: { width: 160, height: 120 },
      environment: { color: [0.5, 0.6, 0.8], intensity: 0.4 },
      ground: groundRough,
      lights: [{ position: [2, 4, 2], radius: 0.5, intensity: 25 }],
      meshes: [
        { file: 'meshes/ico-flat.obj', position: [-0.8, 0.7, 0.1], rotation: [30, 45, 60], scale: [1.4, 0.6, 0.9], material: { color: [0.9, 0.5, 0.3], roughness: 0.3 } },
        { file: 'meshes/ico-smooth-le.ply', position: [0.9, 0.6, -0.2], rotation: [-20, 110, 35], scale: [0.5, 0.9, 0.7], material: { color: [0.3, 0.7, 0.9], roughness: 1 } },
      ],
    },
  },
  'gltf-nodes': {
    note: 'ico-nodes.gltf (node translation/scale, parent with child rotation) + mesh rotation [0,30,15], scale 0.35',
    scene: {
      version: 2,
      camera: { position: [0, 1.2, 5], target: [0, 0.8, 0], fov: 45 },
      image: { width: 160, height: 120 },
      environment: { map: 'envmaps/studio.exr', intensity: 0.6 },
      ground: groundRough,
      meshes: [
        { file: 'meshes/ico-nodes.gltf', position: [-0.2, 0.4, 0], rotation: [0, 30, 15], scale: 0.35, material: { color: [0.8, 0.8, 0.75], roughness: 0.3 } },
      ],
    },
  },
  'flat-smooth': {
    note: 'flat vs smooth icospheres, r 0.3 and r 1, four file formats (obj, ply LE, glb, gltf), mesh non-uniform scale',
    scene: {
      version: 2,
      camera: { position: [0, 2.2, 5.5], target: [0, 0.5, 0], fov: 35 },
      image: { width: 160, height: 120 },
      environment: { color: [0.6, 0.7, 0.9], intensity: 0.3 },
      ground: groundRough,
      lights: [{ position: [-2, 4, 3], radius: 0.6, intensity: 20 }],
      meshes: [
        { file: 'meshes/ico-flat.obj', position: [-1.8, 0.5, 0], scale: 0.5, material: { color: [0.9, 0.9, 0.9], roughness: 0.3 } },
        { file: 'meshes/ico-smooth-le.ply', position: [-0.6, 0.5, 0], scale: 0.5, material: { color: [0.9, 0.9, 0.9], roughness: 0.3 } },
        { file: 'meshes/ico-flat.glb', position: [0.6, 0.5, 0], scale: [0.5, 0.5, 0.3], material: { color: [0.9, 0.9, 0.9], roughness: 1 } },
        { file: 'meshes/ico-smooth.gltf', position: [1.8, 0.5, 0], scale: [0.5, 0.5, 0.3], material: { color: [0.9, 0.9, 0.9], roughness: 1 } },
      ],
    },
  },
  'emissive-sides': {
    note: 'open emissive quads seen from front and back (one-sided emission, two-sided BSDF), coloured emissive sphere',
    scene: {
      version: 2,
      camera: { position: [0, 1.2, 4.5], target: [0, 0.6, 0], fov: 50 },
      image: { width: 160, height: 120 },
      environment: { color: [0.02, 0.02, 0.03], intensity: 1 },
      ground: { height: 0, material: { color: [0.7, 0.7, 0.7], roughness: 0.5 } },
      spheres: [
        { center: [0, 0.4, 0.3], radius: 0.4, material: { color: [0.5, 0.5, 0.5], roughness: 0.5, emission: { color: [0.2, 0.6, 1.0], intensity: 5 } } },
      ],
      meshes: [
        // Faces the camera (+z after a 20 degree turn): emits toward it.
        { file: 'meshes/quad.obj', position: [-1.3, 0.7, 0], rotation: [0, 20, 0], scale: [0.8, 1.2, 1], material: { color: [0.8, 0.8, 0.8], roughness: 0.6, emission: { color: [1, 0.6, 0.3], intensity: 3 } } },
        // Turned away (200 degrees): the camera sees its back (no emission), its front lights the ground behind.
        { file: 'meshes/quad.obj', position: [1.3, 0.7, 0], rotation: [0, 200, 0], scale: [0.8, 1.2, 1], material: { color: [0.8, 0.8, 0.8], roughness: 0.6, emission: { color: [1, 0.6, 0.3], intensity: 3 } } },
      ],
    },
  },
  'emissive-smooth-mesh': {
    note: 'smooth (vertex-normal) emissive icosphere, 80 faces, non-uniform scale, lighting a rough ground and spheres (NEE on a mesh whose shading normals differ from its faces)',
    scene: {
      version: 2,
      camera: { position: [0, 1.5, 4.5], target: [0, 0.5, 0], fov: 40 },
      image: { width: 160, height: 120 },
      render: { maxBounces: 3 },
      environment: { color: [0.02, 0.02, 0.03], intensity: 1 },
      ground: { height: 0, material: { color: [0.7, 0.7, 0.7], roughness: 1 } },
      spheres: [
        { center: [-1.1, 0.4, 0.3], radius: 0.4, material: { color: [0.8, 0.8, 0.8], roughness: 1 } },
        { center: [1.1, 0.4, 0.3], radius: 0.4, material: { color: [0.9, 0.7, 0.5], roughness: 0.4 } },
      ],
      meshes: [
        { file: 'meshes/ico-smooth.obj', position: [0, 0.9, -0.3], rotation: [0, 15, 0], scale: [0.5, 0.35, 0.4], material: { color: [0.5, 0.5, 0.5], roughness: 1, emission: { color: [1, 0.85, 0.6], intensity: 5 } } },
      ],
    },
  },
  'mixed-emitters': {
    note: 'envmap (studio, rotation 200) + coloured light + emissive glass sphere + emissive smooth mirror mesh (r 0) + emissive rough-glass mesh; light choice among four kinds',
    spp: 768,
    scene: {
      version: 2,
      camera: { position: [0.3, 1.3, 4.2], target: [0, 0.5, 0], fov: 42 },
      image: { width: 160, height: 120 },
      render: { maxBounces: 5 },
      environment: { map: 'envmaps/studio.exr', intensity: 0.3, rotation: 200 },
      ground: { height: 0, material: { color: [0.6, 0.6, 0.6], roughness: 0.8 } },
      lights: [{ position: [-2, 3, 1], radius: 0.3, color: '#ffcc88', intensity: 20 }],
      spheres: [
        { center: [-1.1, 0.45, 0], radius: 0.45, material: { type: 'dielectric', ior: 1.5, color: [0.9, 0.95, 1], emission: { color: [0.3, 1, 0.4], intensity: 1.5 } } },
        { center: [1.2, 0.35, 0.5], radius: 0.35, material: { color: [0.8, 0.8, 0.8], roughness: 1 } },
      ],
      meshes: [
        { file: 'meshes/ico-smooth.obj', position: [0.1, 0.5, -0.4], scale: 0.5, material: { color: [0.9, 0.9, 0.9], roughness: 0, emission: { color: [1, 0.3, 0.2], intensity: 2 } } },
        { file: 'meshes/ico-flat.obj', position: [1.2, 1.1, -0.6], rotation: [20, 0, 40], scale: 0.3, material: { type: 'dielectric', ior: 1.33, roughness: 0.4, emission: { color: [0.4, 0.5, 1], intensity: 3 } } },
      ],
    },
  },
  'bounces-0': {
    note: 'maxBounces 0: the camera sees emitters (light, emissive sphere, emissive mesh front/back) and the rotated map only',
    spp: 128,
    scene: {
      version: 2,
      camera: { position: [0, 1, 4], target: [0, 0.6, 0], fov: 50 },
      image: { width: 160, height: 120 },
      render: { maxBounces: 0 },
      environment: { map: 'envmaps/sunset.hdr', intensity: 0.8, rotation: 135 },
      ground: { height: 0, material: { color: [0.6, 0.6, 0.6], roughness: 1 } },
      lights: [{ position: [-1.5, 1.2, 0], radius: 0.3, intensity: 3 }],
      spheres: [{ center: [0, 0.5, 0], radius: 0.4, material: { color: [0.5, 0.5, 0.5], roughness: 0.5, emission: { color: '#3366ff', intensity: 2 } } }],
      meshes: [
        { file: 'meshes/ico-smooth.obj', position: [1.4, 0.6, 0], scale: 0.4, material: { emission: { color: [1, 0.5, 0.1], intensity: 1.5 } } },
        { file: 'meshes/quad.obj', position: [0.8, 1.5, 0], rotation: [0, 160, 0], scale: 0.5, material: { emission: { intensity: 2 } } },
      ],
    },
  },
  'mirror-ground': {
    note: 'mirror ground (r 0) and glossy ground tint under a rotated envmap, camera low, wide fov 70, diffuse + rough-conductor spheres',
    scene: {
      version: 2,
      camera: { position: [0, 0.6, 3.5], target: [0, 0.5, 0], fov: 70 },
      image: { width: 160, height: 120 },
      render: { maxBounces: 6 },
      environment: { map: 'envmaps/sunset.hdr', intensity: 0.6, rotation: -75 },
      ground: { height: 0, material: { color: [0.7, 0.75, 0.8], roughness: 0 } },
      spheres: [
        { center: [-0.8, 0.5, 0], radius: 0.5, material: { color: [0.8, 0.3, 0.3], roughness: 1 } },
        { center: [0.8, 0.5, 0], radius: 0.5, material: { color: [0.9, 0.9, 0.9], roughness: 0.2 } },
      ],
    },
  },
  'rough-glass-spheres': {
    note: 'rough dielectric spheres: r 0.3 ior 1.33 tint [0.7,0.9,1]; r 0.7 ior 2.4 tint [1,0.8,0.6]; r 0.3 ior 2.4',
    spp: 768,
    scene: {
      version: 2,
      camera: { position: [0, 1.4, 5], target: [0, 0.6, 0], fov: 38 },
      image: { width: 160, height: 120 },
      render: { maxBounces: 8 },
      environment: { color: [0.6, 0.7, 0.9], intensity: 0.5 },
      ground: { height: 0, material: { color: [0.75, 0.75, 0.72], roughness: 1 } },
      lights: [{ position: [2, 4, 1], radius: 0.6, intensity: 25 }],
      spheres: [
        { center: [-1.3, 0.6, 0], radius: 0.6, material: { type: 'dielectric', ior: 1.33, roughness: 0.3, color: [0.7, 0.9, 1.0] } },
        { center: [0, 0.6, -0.3], radius: 0.6, material: { type: 'dielectric', ior: 2.4, roughness: 0.7, color: [1.0, 0.8, 0.6] } },
        { center: [1.3, 0.6, 0], radius: 0.6, material: { type: 'dielectric', ior: 2.4, roughness: 0.3 } },
      ],
    },
  },
  'rough-glass-meshes': {
    note: 'rough dielectric closed meshes: smooth ico r 0.3 ior 2.4 tint; flat ico (scaled [1,0.7,1.2], rotated) r 0.7 ior 1.33 tint; gem r 0.3',
    spp: 768,
    scene: {
      version: 2,
      camera: { position: [0, 1.4, 5], target: [0, 0.6, 0], fov: 38 },
      image: { width: 160, height: 120 },
      render: { maxBounces: 8 },
      environment: { map: 'envmaps/sunset.hdr', intensity: 0.7, rotation: -40 },
      ground: { height: 0, material: { color: [0.75, 0.75, 0.72], roughness: 1 } },
      meshes: [
        { file: 'meshes/ico-smooth.obj', position: [-1.3, 0.6, 0], scale: 0.6, material: { type: 'dielectric', ior: 2.4, roughness: 0.3, color: [0.8, 1.0, 0.8] } },
        { file: 'meshes/ico-flat-le.ply', position: [0, 0.6, -0.3], rotation: [10, 25, -15], scale: [0.6, 0.42, 0.72], material: { type: 'dielectric', ior: 1.33, roughness: 0.7, color: [1.0, 0.85, 0.7] } },
        { file: 'meshes/gem.obj', position: [1.3, 0.45, 0], scale: 0.45, material: { type: 'dielectric', ior: 1.5, roughness: 0.3 } },
      ],
    },
  },
  'envmap-rot90': {
    note: 'sunset.hdr rotation 90 intensity 0.5; glossy spheres r 0.3 / 0.1 / mirror; rough ground; fov 60',
    scene: {
      version: 2,
      camera: { position: [0.5, 1.0, 3.5], target: [0, 0.5, 0], fov: 60 },
      image: { width: 160, height: 120 },
      environment: { map: 'envmaps/sunset.hdr', intensity: 0.5, rotation: 90 },
      ground: { height: 0, material: { color: [0.5, 0.5, 0.5], roughness: 0.5 } },
      spheres: [
        { center: [-1.1, 0.5, 0], radius: 0.5, material: { color: [0.9, 0.9, 0.9], roughness: 0.3 } },
        { center: [0, 0.5, -0.4], radius: 0.5, material: { color: [0.9, 0.7, 0.4], roughness: 0.1 } },
        { center: [1.1, 0.5, 0], radius: 0.5, material: { color: [0.95, 0.95, 0.95], roughness: 0 } },
      ],
    },
  },
  'bounces-2': {
    note: 'maxBounces 2, narrow fov 25, thin lens (aperture 0.05), mesh + spheres under a light',
    scene: {
      version: 2,
      camera: { position: [0, 2, 7], target: [0, 0.5, 0], fov: 25, aperture: 0.05 },
      image: { width: 160, height: 120 },
      render: { maxBounces: 2 },
      environment: { color: [0.4, 0.5, 0.7], intensity: 0.3 },
      ground: { height: 0, material: { color: [0.8, 0.8, 0.8], roughness: 0.4 } },
      lights: [{ position: [1.5, 3, 2], radius: 0.4, intensity: 40 }],
      spheres: [
        { center: [-0.9, 0.5, 0], radius: 0.5, material: { color: [0.95, 0.95, 0.95], roughness: 0 } },
        { center: [0.2, 0.3, 0.8], radius: 0.3, material: { type: 'dielectric', ior: 1.5 } },
      ],
      meshes: [{ file: 'meshes/ico-smooth.obj', position: [0.9, 0.55, -0.2], rotation: [0, 0, 30], scale: [0.6, 0.5, 0.5], material: { color: [0.8, 0.3, 0.3], roughness: 0.3 } }],
    },
  },
  'bounces-large': {
    note: 'maxBounces 40, white-ish diffuse/glossy interreflection between a large mesh wall and spheres, smooth glass',
    scene: {
      version: 2,
      camera: { position: [0, 1.2, 4], target: [0, 0.7, 0], fov: 45 },
      image: { width: 160, height: 120 },
      render: { maxBounces: 40 },
      environment: { color: [0.9, 0.9, 1.0], intensity: 0.5 },
      ground: { height: 0, material: { color: [0.9, 0.9, 0.9], roughness: 1 } },
      spheres: [
        { center: [-0.8, 0.6, 0], radius: 0.6, material: { color: [0.95, 0.95, 0.95], roughness: 1 } },
        { center: [0.8, 0.6, 0], radius: 0.6, material: { color: [0.95, 0.9, 0.8], roughness: 0.5 } },
        { center: [0, 0.3, 0.9], radius: 0.3, material: { type: 'dielectric', ior: 1.5 } },
      ],
      meshes: [{ file: 'meshes/quad.obj', position: [0, 1.5, -1], scale: [4, 3, 1], material: { color: [0.95, 0.95, 0.95], roughness: 1 } }],
    },
  },
};

function arg(name: string): string | undefined {
  const i = process.argv.indexOf(name);
  return i >= 0 ? process.argv[i + 1] : undefined;
}

function setUp(dir: string, name: string, audit: AuditScene): string {
  const sceneDir = path.join(dir, name);
  mkdirSync(path.join(sceneDir, 'meshes'), { recursive: true });
  mkdirSync(path.join(sceneDir, 'envmaps'), { recursive: true });
  const scene = audit.scene;
  const files: string[] = (scene.meshes as Json[] | undefined)?.map((m) => m.file as string) ?? [];
  const env = scene.environment as Json | undefined;
  if (env && typeof env.map === 'string') files.push(env.map);
  for (const file of files) {
    const target = path.join(sceneDir, file);
    if (file === 'meshes/quad.obj') writeFileSync(target, QUAD_OBJ);
    else copyFileSync(path.join(FIXTURES, file), target);
  }
  const file = path.join(sceneDir, 'scene.json');
  writeFileSync(file, JSON.stringify(scene, null, 2) + '\n');
  return file;
}

function toImage(pfm: { width: number; height: number; rgb: Float32Array }): LinearImage {
  return { width: pfm.width, height: pfm.height, channels: 3, data: pfm.rgb };
}

/**
 * Mitsuba 3.9.1 leaves an occasional NaN pixel (seen under studio.exr, whose
 * texels include negative values): replace each by the mean of its finite
 * 4-neighbours so one pixel does not turn every measure into NaN. Returns the count.
 */
function patchNaNs(image: LinearImage): number {
  const { width, height, data } = image;
  let count = 0;
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      for (let c = 0; c < 3; c++) {
        const i = (y * width + x) * 3 + c;
        if (Number.isFinite(data[i])) continue;
        count++;
        let sum = 0, n = 0;
        for (const [dx, dy] of [[1, 0], [-1, 0], [0, 1], [0, -1]]) {
          const [nx, ny] = [x + dx, y + dy];
          if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
          const v = data[(ny * width + nx) * 3 + c];
          if (Number.isFinite(v)) [sum, n] = [sum + v, n + 1];
        }
        data[i] = n > 0 ? sum / n : 0;
      }
    }
  }
  return count;
}

/** The Mitsuba reference, made exactly as scripts/make-reference.sh makes it; cached by scene text and spp. */
function reference(sceneFile: string, spp: number): { image: LinearImage; seconds: number } {
  const dir = path.dirname(sceneFile);
  const key = `${readFileSync(sceneFile, 'utf8')}\nspp ${spp}\n`;
  const out = path.join(dir, 'reference.pfm');
  const keyFile = path.join(dir, 'reference.key');
  let seconds = 0;
  if (!(existsSync(out) && existsSync(keyFile) && readFileSync(keyFile, 'utf8') === key)) {
    const xml = path.join(dir, 'scene.xml');
    execFileSync('node', [path.join(ROOT, 'bin/pathtrace.js'), 'export-mitsuba', sceneFile, '-o', xml, '--spp', String(spp)], { stdio: ['ignore', 'ignore', 'inherit'] });
    const line = execFileSync('python3', [path.join(ROOT, 'bench/mitsuba/render.py'), xml, '--out', out, '--spp', String(spp)], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] });
    seconds = JSON.parse(line.trim().split('\n').pop()!).seconds;
    writeFileSync(keyFile, key);
  }
  const image = toImage(decodePfm(readFileSync(out)));
  const nans = patchNaNs(image);
  if (nans > 0) console.log(`  (reference: ${nans} non-finite pixel values patched from their neighbours)`);
  return { image, seconds };
}

function channelMeans(image: LinearImage): number[] {
  const sums = [0, 0, 0];
  for (let p = 0; p < image.width * image.height; p++) for (let c = 0; c < 3; c++) sums[c] += image.data[p * image.channels + c];
  return sums.map((s) => s / (image.width * image.height));
}

function rgba(image: LinearImage): Float32Array {
  const out = new Float32Array(image.width * image.height * 4);
  for (let p = 0; p < image.width * image.height; p++) {
    for (let c = 0; c < 3; c++) out[p * 4 + c] = image.data[p * image.channels + c];
    out[p * 4 + 3] = 1;
  }
  return out;
}

interface Result {
  name: string;
  relMse: number;
  predicted: number;
  ratio: number[];
  meanZ: number[];
  worstZ: number;
  worstZAt: string;
  worstRel: number;
  worstRelAt: string;
  worstExcess: number;
  flagged: boolean;
  oursSeconds: number;
  refSeconds: number;
}

async function main(): Promise<void> {
  const only = arg('--only')?.split(',');
  const refSpp = Number(arg('--ref-spp') ?? 4096);
  const defaultSpp = Number(arg('--spp') ?? 512);
  const dir = process.env.AUDIT_DIR ?? '/tmp/audit-v2';
  const names = Object.keys(SCENES).filter((n) => !only || only.includes(n));
  for (const n of only ?? []) if (!SCENES[n]) throw new Error(`unknown scene ${n}; known: ${Object.keys(SCENES).join(', ')}`);
  // AUDIT_WEB_ROOT: another build of the page (e.g. `npx vite build --outDir /tmp/web-before` of an older commit) to compare.
  const session = await openRenderSession(process.env.AUDIT_WEB_ROOT ? { webRoot: process.env.AUDIT_WEB_ROOT } : {});
  const results: Result[] = [];
  try {
    for (const name of names) {
      const audit = SCENES[name];
      const sceneFile = setUp(dir, name, audit);
      const ref = reference(sceneFile, audit.refSpp ?? refSpp);
      const scene = parseSceneText(readFileSync(sceneFile, 'utf8'));
      const { files } = await readSceneFiles(scene, sceneFile);
      const spp = audit.spp ?? defaultSpp;
      const start = performance.now();
      const batches: LinearImage[] = [];
      for (let seed = 1; seed <= BATCHES; seed++) {
        await session.load(scene, { width: scene.image.width, height: scene.image.height, seed }, files);
        await session.render(spp / BATCHES);
        batches.push({ width: scene.image.width, height: scene.image.height, channels: 4, data: await session.readLinear() });
      }
      const oursSeconds = (performance.now() - start) / 1000;
      const image = average(batches);
      const variance = varianceOfMean(batches, image);
      const reference_ = ref.image;
      writeFileSync(path.join(dir, name, 'ours.pfm'), encodePfm(image.width, image.height, image.data));

      const refNoise = (0.01 / BLOCK) * Math.sqrt(16384 / (audit.refSpp ?? refSpp));
      const floor = 0.02 * meanValue(reference_);
      const sigma = blockMeans(variance, BLOCK).means.map((v) => Math.sqrt(v / (BLOCK * BLOCK)));
      const refMeans = blockMeans(reference_, BLOCK).means;
      const ourMeans = blockMeans(image, BLOCK).means;
      const cols = Math.floor(image.width / BLOCK);
      const at = (i: number) => `(${Math.floor(i / 3) % cols},${Math.floor(Math.floor(i / 3) / cols)}) ${'rgb'[i % 3]} ${ourMeans[i].toFixed(4)} vs ${refMeans[i].toFixed(4)}`;
      let worstZ = 0, worstZAt = '', worstRel = 0, worstRelAt = '', worstExcess = 0;
      for (let i = 0; i < refMeans.length; i++) {
        const scale = refMeans[i] + floor;
        const relSigma = Math.hypot(sigma[i] / scale, refNoise);
        const rel = Math.abs(ourMeans[i] - refMeans[i]) / scale;
        const z = rel / relSigma;
        if (z > worstZ) [worstZ, worstZAt] = [z, at(i)];
        if (rel > worstRel) [worstRel, worstRelAt] = [rel, at(i)];
        worstExcess = Math.max(worstExcess, rel - 2 * relSigma);
      }
      const predicted = predictedRelMse(variance, reference_);
      const ours = channelMeans(image);
      const theirs = channelMeans(reference_);
      // z of the whole image's mean per channel: our variance of the mean, plus the
      // reference's, estimated as ours scaled by spp / refSpp (similar per-sample variance).
      const n = image.width * image.height;
      const meanZ = [0, 1, 2].map((c) => {
        let v = 0;
        for (let p = 0; p < n; p++) v += variance.data[p * 4 + c];
        v /= n * n;
        return (ours[c] - theirs[c]) / Math.sqrt(v * (1 + spp / (audit.refSpp ?? refSpp)) + 1e-30);
      });
      const result: Result = {
        name,
        relMse: relativeMse(image, reference_),
        predicted,
        ratio: ours.map((o, c) => o / theirs[c]),
        meanZ,
        worstZ,
        worstZAt,
        worstRel,
        worstRelAt,
        worstExcess,
        flagged: worstZ > Z_FLAG || worstExcess > REL_FLAG,
        oursSeconds,
        refSeconds: ref.seconds,
      };
      results.push(result);
      console.log(
        `${result.flagged ? 'FLAG' : 'ok  '} ${name}: relMSE ${result.relMse.toExponential(2)} (noise ${predicted.toExponential(2)}), ` +
          `mean ratio ${result.ratio.map((r) => r.toFixed(4)).join('/')} (z ${meanZ.map((z) => z.toFixed(1)).join('/')}), worst z ${worstZ.toFixed(2)} at ${worstZAt}, ` +
          `worst rel ${(worstRel * 100).toFixed(2)}% at ${worstRelAt} (beyond 2 sigma: ${(Math.max(0, worstExcess) * 100).toFixed(2)}%), ` +
          `ours ${spp} spp ${oursSeconds.toFixed(0)} s, mitsuba ${ref.seconds ? ref.seconds.toFixed(0) + ' s' : 'cached'}`,
      );
    }
  } finally {
    await session.close();
  }
  console.log('\n| scene | relMSE (noise) | mean ratio R/G/B | z of mean R/G/B | worst block z | worst block rel. err | flagged |');
  console.log('| --- | --- | --- | --- | --- | --- | --- |');
  for (const r of results) {
    console.log(
      `| ${r.name} | ${r.relMse.toExponential(2)} (${r.predicted.toExponential(2)}) | ${r.ratio.map((x) => x.toFixed(4)).join(' / ')} | ${r.meanZ.map((x) => x.toFixed(1)).join(' / ')} | ` +
        `${r.worstZ.toFixed(1)} | ${(r.worstRel * 100).toFixed(1)}% | ${r.flagged ? 'yes' : 'no'} |`,
    );
  }
  if (results.some((r) => r.flagged)) process.exitCode = 1;
}

main().catch((error) => {
  console.error(error);
  process.exit(2);
});
