/**
 * Export a normalized scene as a Mitsuba 3 XML scene (scene format versions
 * 1 and 2 -> `<scene version="3.0.0">`). Used by `pathtrace export-mitsuba` and by the
 * benchmark, which renders the same scene with Mitsuba at equal time.
 *
 * Pure: no DOM, no Node APIs. The mapping, and why each choice matches the
 * scene contract (docs/scene-format.md):
 * - camera: `perspective` (or `thinlens` when aperture > 0), fov_axis="y",
 *   to_world = lookat(position, target, up). Mitsuba's lookat puts image right
 *   at cross(forward, up) and row 0 at the top, as the format does. We pass the
 *   orthonormal up of `cameraFrame`, so a degenerate `up` gets the same
 *   fallback the renderer uses.
 * - film: `hdrfilm`, pixel_format rgb, box rfilter (radius 0.5 = uniform jitter
 *   inside the pixel, the format's pixel definition).
 * - integrator: `path`, max_depth = maxBounces + 1, rr_depth > max_depth so
 *   Russian roulette never runs (the references were rendered that way).
 * - standard material: `blendbsdf` with weight = roughness, first child the
 *   specular lobe, second `diffuse`: Mitsuba evaluates (1 - w) * first + w *
 *   second, which is the format's (1 - r) * Specular + r * Lambert. Specular
 *   is `conductor` (r = 0) or `roughconductor` with GGX, alpha = r^2, and
 *   material="none" (reflectance 1 at all angles = no Fresnel) tinted by
 *   specular_reflectance. Pure r = 0 and r = 1 skip the blend. One-sided, as
 *   the format says for spheres and the ground (Mitsuba's default).
 * - dielectric: `dielectric` (r = 0) or `roughdielectric` (GGX, alpha = r^2,
 *   visible normals), int_ior = ior, ext_ior = 1, specular_transmittance =
 *   color.
 * - emission: an `area` emitter on the shape.
 * - environment map: `envmap` with scale = intensity, rotated about +y; the
 *   file name as `environmentMapPath` gives it (default: as in the scene).
 * - meshes: a `ply` shape per mesh whose file `meshPath(i)` names: the
 *   caller writes it with `meshPlyFile` (world-space triangles, vertex
 *   normals when smooth; `face_normals` when flat, since Mitsuba would
 *   otherwise smooth them). Standard materials on meshes are `twosided`.
 * - lights: `sphere` with an `area` emitter (one-sided, emitting along the
 *   outward normal: the format's "all outward directions") and a black
 *   `diffuse` BSDF (lights reflect nothing).
 * - ground: a `rectangle` (normal +z, [-1, 1]^2) scaled to 40000 x 40000,
 *   rotated so its normal is +y, at y = height, centered under the camera
 *   (so a camera far from the origin still sees ground to the horizon; for
 *   cameras near the origin the edges lie ~20000 away, beyond far_clip, so it
 *   makes no difference to the image).
 * - clipping: near_clip 1e-4 (Mitsuba's 0.01 would cut objects close to the
 *   lens); far_clip stays at Mitsuba's default 1e4, as in the references: see
 *   farClip().
 * - environment: `constant` emitter, omitted when null or black.
 */
import { cameraFrame } from './camera';
import { encodePly } from './mesh/plyEncode';
import { transformMesh } from './mesh/transform';
import type { Camera, DielectricMaterial, Material, Mesh, Scene, StandardMaterial, TriangleMesh, Vec3 } from './types';

export interface MitsubaExportOptions {
  /** Samples per pixel written into the sampler (default 256). */
  spp?: number;
  /** Film size; defaults to scene.image. */
  width?: number;
  height?: number;
  /** Seed of the `independent` sampler (default 0). */
  seed?: number;
  /** The file name to write for `environment.map` (e.g. resolved against the scene file). Default: as written. */
  environmentMapPath?: (map: string) => string;
  /** The PLY file written for meshes[i] (see meshPlyFile). Required when the scene has meshes. */
  meshPath?: (index: number) => string;
  /** Whether meshes[i]'s file gives vertex normals (smooth); flat meshes get `face_normals`. Default: smooth. */
  meshSmooth?: (index: number) => boolean;
}

/** The PLY bytes the export of meshes[i] refers to: its triangles in world space (`data` is the decoded file). */
export function meshPlyFile(mesh: Mesh, data: TriangleMesh): Uint8Array {
  return encodePly(transformMesh(data, mesh));
}

/** Side of the square that stands in for the infinite ground plane. */
export const MITSUBA_GROUND_SIZE = 40000;
export const MITSUBA_DEFAULT_SPP = 256;
/** Mitsuba's default near clip (0.01) would cut objects close to the lens. */
const NEAR_CLIP = 1e-4;
const MITSUBA_DEFAULT_FAR_CLIP = 1e4;

/** Escape a string for use inside an XML attribute value or text. */
export function escapeXml(value: string): string {
  return value
    .replace(/&/g, '&amp;')
    .replace(/</g, '&lt;')
    .replace(/>/g, '&gt;')
    .replace(/"/g, '&quot;')
    .replace(/'/g, '&apos;');
}

/** Shortest round-trip decimal form; non-finite numbers are a caller bug. */
function num(x: number): string {
  if (!Number.isFinite(x)) throw new Error(`toMitsubaXml: non-finite number ${x}`);
  return String(x);
}

function int(x: number, name: string): string {
  if (!Number.isInteger(x) || x < 0) throw new Error(`toMitsubaXml: ${name} must be a non-negative integer, got ${x}`);
  return String(x);
}

function triple(v: readonly number[]): string {
  return `${num(v[0])}, ${num(v[1])}, ${num(v[2])}`;
}

function scale3(v: Vec3, s: number): Vec3 {
  return [v[0] * s, v[1] * s, v[2] * s];
}

function isBlack(v: Vec3): boolean {
  return v[0] === 0 && v[1] === 0 && v[2] === 0;
}

/** A tiny XML element tree, serialized with two-space indentation. */
interface Node {
  tag: string;
  attrs: [string, string][];
  children: Node[];
}

function el(tag: string, attrs: Record<string, string>, children: Node[] = []): Node {
  return { tag, attrs: Object.entries(attrs), children };
}

function serialize(node: Node, depth: number, out: string[]): void {
  const pad = '  '.repeat(depth);
  const attrs = node.attrs.map(([k, v]) => ` ${k}="${escapeXml(v)}"`).join('');
  if (node.children.length === 0) {
    out.push(`${pad}<${node.tag}${attrs}/>`);
    return;
  }
  out.push(`${pad}<${node.tag}${attrs}>`);
  for (const child of node.children) serialize(child, depth + 1, out);
  out.push(`${pad}</${node.tag}>`);
}

const float = (name: string, value: number) => el('float', { name, value: num(value) });
const integer = (name: string, value: number) => el('integer', { name, value: int(value, name) });
const str = (name: string, value: string) => el('string', { name, value });
const rgb = (name: string, value: Vec3) => el('rgb', { name, value: triple(value) });
const point = (name: string, value: Vec3) => el('point', { name, value: triple(value) });

function sensor(camera: Camera, width: number, height: number, spp: number, seed: number, farClip: number): Node {
  const frame = cameraFrame(camera);
  if (![...frame.forward, ...frame.up].every(Number.isFinite)) {
    throw new Error('toMitsubaXml: camera.position and camera.target must differ');
  }
  const thinLens = camera.aperture > 0;
  const lens = thinLens
    ? [float('aperture_radius', camera.aperture), float('focus_distance', frame.focusDistance)]
    : [];
  return el('sensor', { type: thinLens ? 'thinlens' : 'perspective' }, [
    str('fov_axis', 'y'),
    float('fov', camera.fov),
    float('near_clip', NEAR_CLIP),
    float('far_clip', farClip),
    ...lens,
    el('transform', { name: 'to_world' }, [
      el('lookat', { origin: triple(camera.position), target: triple(camera.target), up: triple(frame.up) }),
    ]),
    el('sampler', { type: 'independent' }, [integer('sample_count', spp), integer('seed', seed)]),
    el('film', { type: 'hdrfilm' }, [
      integer('width', width),
      integer('height', height),
      str('pixel_format', 'rgb'),
      el('rfilter', { type: 'box' }),
    ]),
  ]);
}

/** The format's material as a Mitsuba BSDF. */
function materialBsdf(material: Material): Node {
  return material.type === 'dielectric' ? dielectricBsdf(material) : standardBsdf(material);
}

function dielectricBsdf(m: DielectricMaterial): Node {
  const common = [float('int_ior', m.ior), float('ext_ior', 1), rgb('specular_transmittance', m.color)];
  if (m.roughness === 0) return el('bsdf', { type: 'dielectric' }, common);
  return el('bsdf', { type: 'roughdielectric' }, [
    str('distribution', 'ggx'),
    float('alpha', m.roughness * m.roughness),
    el('boolean', { name: 'sample_visible', value: 'true' }),
    ...common,
  ]);
}

/** (1 - r) * GGX conductor + r * Lambert. */
function standardBsdf(material: StandardMaterial): Node {
  const r = material.roughness;
  const diffuse = el('bsdf', { type: 'diffuse' }, [rgb('reflectance', material.color)]);
  const specular =
    r === 0
      ? el('bsdf', { type: 'conductor' }, [str('material', 'none'), rgb('specular_reflectance', material.color)])
      : el('bsdf', { type: 'roughconductor' }, [
          str('material', 'none'),
          str('distribution', 'ggx'),
          float('alpha', r * r),
          el('boolean', { name: 'sample_visible', value: 'true' }),
          rgb('specular_reflectance', material.color),
        ]);
  // blendbsdf: weight 0 selects the first child, 1 the second.
  return r === 0 ? specular : r === 1 ? diffuse : el('bsdf', { type: 'blendbsdf' }, [float('weight', r), specular, diffuse]);
}

/** The `area` emitter of an emissive material, if any. */
function areaEmitter(material: Material): Node[] {
  const e = material.emission;
  const radiance = e ? scale3(e.color, e.intensity) : ([0, 0, 0] as Vec3);
  return isBlack(radiance) ? [] : [el('emitter', { type: 'area' }, [rgb('radiance', radiance)])];
}

function environmentEmitter(scene: Scene, opts: MitsubaExportOptions): Node | null {
  const e = scene.environment;
  if (!e) return null;
  if ('map' in e) {
    return el('emitter', { type: 'envmap' }, [
      str('filename', opts.environmentMapPath ? opts.environmentMapPath(e.map) : e.map),
      float('scale', e.intensity),
      el('transform', { name: 'to_world' }, [el('rotate', { y: '1', angle: num(e.rotation) })]),
    ]);
  }
  const radiance = scale3(e.color, e.intensity);
  return isBlack(radiance) ? null : el('emitter', { type: 'constant' }, [rgb('radiance', radiance)]);
}

function groundShape(scene: Scene): Node | null {
  if (!scene.ground) return null;
  const [cx, , cz] = scene.camera.position;
  return el('shape', { type: 'rectangle' }, [
    el('transform', { name: 'to_world' }, [
      el('scale', { value: num(MITSUBA_GROUND_SIZE / 2) }),
      // Rotating -90 degrees about x maps the rectangle's normal +z to +y.
      el('rotate', { x: '1', angle: '-90' }),
      el('translate', { value: triple([cx, scene.ground.height, cz]) }),
    ]),
    materialBsdf(scene.ground.material),
  ]);
}

/**
 * Mitsuba's default far clip, 1e4, which the reference images were rendered
 * with: a primary ray that would meet the ground further than 1e4 away sees
 * the environment instead (a sliver of about cameraHeight / 1e4 radians just
 * below the horizon). We keep it so exports match the references, and only
 * push it out when spheres or lights lie further away.
 */
function farClip(scene: Scene): number {
  const p = scene.camera.position;
  const dist = (c: Vec3) => Math.hypot(c[0] - p[0], c[1] - p[1], c[2] - p[2]);
  let extent = 0;
  for (const s of scene.spheres) extent = Math.max(extent, dist(s.center) + s.radius);
  for (const l of scene.lights) extent = Math.max(extent, dist(l.position) + l.radius);
  return Math.max(MITSUBA_DEFAULT_FAR_CLIP, 2 * extent);
}

/** A Mitsuba 3 XML scene that renders, on average, the image the format defines. */
export function toMitsubaXml(scene: Scene, opts: MitsubaExportOptions = {}): string {
  const width = opts.width ?? scene.image.width;
  const height = opts.height ?? scene.image.height;
  const spp = opts.spp ?? MITSUBA_DEFAULT_SPP;
  const seed = opts.seed ?? 0;
  const maxDepth = scene.render.maxBounces + 1;

  const children: Node[] = [
    el('integrator', { type: 'path' }, [integer('max_depth', maxDepth), integer('rr_depth', maxDepth + 1)]),
    sensor(scene.camera, width, height, spp, seed, farClip(scene)),
  ];
  const env = environmentEmitter(scene, opts);
  if (env) children.push(env);
  const ground = groundShape(scene);
  if (ground) children.push(ground);
  for (const light of scene.lights) {
    const radiance = scale3(light.color, light.intensity);
    children.push(
      el('shape', { type: 'sphere' }, [
        point('center', light.position),
        float('radius', light.radius),
        el('bsdf', { type: 'diffuse' }, [rgb('reflectance', [0, 0, 0])]),
        ...(isBlack(radiance) ? [] : [el('emitter', { type: 'area' }, [rgb('radiance', radiance)])]),
      ]),
    );
  }
  for (const sphere of scene.spheres) {
    children.push(
      el('shape', { type: 'sphere' }, [
        point('center', sphere.center),
        float('radius', sphere.radius),
        materialBsdf(sphere.material),
        ...areaEmitter(sphere.material),
      ]),
    );
  }
  scene.meshes.forEach((mesh, i) => {
    if (!opts.meshPath) throw new Error('toMitsubaXml: the scene has meshes; pass meshPath and write meshPlyFile for each');
    const bsdf = materialBsdf(mesh.material);
    children.push(
      el('shape', { type: 'ply' }, [
        str('filename', opts.meshPath(i)),
        el('boolean', { name: 'face_normals', value: String(!(opts.meshSmooth?.(i) ?? true)) }),
        mesh.material.type === 'standard' ? el('bsdf', { type: 'twosided' }, [bsdf]) : bsdf,
        ...areaEmitter(mesh.material),
      ]),
    );
  });

  const out = ['<?xml version="1.0" encoding="utf-8"?>', `<!-- Exported by pathtrace from scene format version ${scene.version}. -->`];
  serialize(el('scene', { version: '3.0.0' }, children), 0, out);
  return out.join('\n') + '\n';
}
