/**
 * Rays over a fixture scene's meshes for the BVH benchmarks (bench/bvh-stats.ts,
 * bench/bvh-kernel-ab.ts), one per pixel in image order so that a kernel
 * drawing them keeps the image's pixel quads: the camera's (no jitter); from
 * a camera hit on a mesh or the ground, a cosine-distributed bounce (closest
 * hit) and a shadow ray to a uniform upper-hemisphere direction (any hit);
 * null where the camera ray hits nothing.
 */
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { readSceneFiles } from '../src/node/sceneFiles';
import { bvhInputs } from '../src/render/geometry/world';
import { buildBvh } from '../src/render/bvh/build';
import { packBvh, triangleTexel, type PackedBvh } from '../src/render/bvh/pack';
import { traverseBvh, type Vec3 } from '../src/render/bvh/traverse';
import { cameraRay } from '../src/scene/camera';
import { parseSceneText } from '../src/scene/schema';
import { projectRoot } from './common';
import { random as seededRandom } from '../test/support/random';

export interface BenchRay {
  origin: Vec3;
  dir: Vec3;
}

export interface SceneRays {
  packed: PackedBvh;
  width: number;
  height: number;
  camera: BenchRay[];
  bounce: (BenchRay | null)[];
  shadow: (BenchRay | null)[];
}

const add = (a: Vec3, b: Vec3, s: number): Vec3 => [a[0] + b[0] * s, a[1] + b[1] * s, a[2] + b[2] * s];
const cross = (a: Vec3, b: Vec3): Vec3 => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const dot = (a: Vec3, b: Vec3) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const normalize = (a: Vec3): Vec3 => {
  const l = Math.hypot(...a);
  return [a[0] / l, a[1] / l, a[2] / l];
};

export async function sceneBvh(sceneName: string): Promise<{ packed: PackedBvh; scene: ReturnType<typeof parseSceneText> }> {
  const sceneFile = sceneName.endsWith('.json') ? sceneName : fileURLToPath(new URL(`test/fixtures/scenes/${sceneName}.json`, projectRoot()));
  const scene = parseSceneText(readFileSync(sceneFile, 'utf8'));
  const { assets } = await readSceneFiles(scene, sceneFile);
  // One world-space BVH of every mesh (no instancing): the traversal benchmarks' rays are world rays.
  const inputs = bvhInputs({ ...scene, meshes: scene.meshes.map((m, i) => ({ ...m, file: `${m.file}#${i}` })) }, { ...assets, meshes: new Map(scene.meshes.map((m, i) => [`${m.file}#${i}`, assets.meshes.get(m.file)!])) }).flat();
  return { packed: packBvh(buildBvh(inputs), inputs), scene };
}

export async function sceneRays(sceneName: string, width: number, height: number, seed = 7): Promise<SceneRays> {
  const { packed, scene } = await sceneBvh(sceneName);
  const random = seededRandom(seed);
  const cosineAround = (n: Vec3): Vec3 => {
    const t = normalize(Math.abs(n[0]) > 0.5 ? cross(n, [0, 1, 0]) : cross(n, [1, 0, 0]));
    const b = cross(n, t);
    const r = Math.sqrt(random()), phi = 2 * Math.PI * random();
    const z = Math.sqrt(Math.max(0, 1 - r * r));
    return normalize(add(add([n[0] * z, n[1] * z, n[2] * z], t, r * Math.cos(phi)), b, r * Math.sin(phi)));
  };
  const tex = packed.texture.data;
  const rays: SceneRays = { packed, width, height, camera: [], bounce: [], shadow: [] };
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const ray = cameraRay(scene.camera, width / height, (x + 0.5) / width, (y + 0.5) / height);
      rays.camera.push({ origin: ray.origin, dir: ray.direction });
      const hit = traverseBvh(packed, ray.origin, ray.direction, Infinity);
      let t = hit ? hit.t : Infinity;
      let normal: Vec3 = [0, 1, 0];
      if (hit) {
        const o = triangleTexel(hit.triangle) * 4;
        const v = (c: number): Vec3 => [tex[o + c * 4], tex[o + c * 4 + 1], tex[o + c * 4 + 2]];
        normal = normalize(cross(add(v(1), v(0), -1), add(v(2), v(0), -1)));
        if (dot(normal, ray.direction) > 0) normal = [-normal[0], -normal[1], -normal[2]];
      } else if (ray.direction[1] < 0 && scene.ground) {
        t = (scene.ground.height - ray.origin[1]) / ray.direction[1];
      }
      if (t === Infinity) {
        rays.bounce.push(null);
        rays.shadow.push(null);
        continue;
      }
      const p = add(add(ray.origin, ray.direction, t), normal, 1e-4);
      rays.bounce.push({ origin: p, dir: cosineAround(normal) });
      let l = normalize([random() * 2 - 1, random(), random() * 2 - 1]);
      if (dot(l, normal) < 0) l = cosineAround(normal);
      rays.shadow.push({ origin: p, dir: l });
    }
  }
  return rays;
}
