/**
 * Export a normalized scene as a Mitsuba 3 XML scene (scene format versions
 * 1 to 3 -> `<scene version="3.0.0">`). Used by `pathtrace export-mitsuba` and by the
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
 *   Russian roulette never runs (the references were rendered that way);
 *   `volpath` (same depths) when a material lets light through anywhere
 *   (opacity below 1 or an opacity texture): a pass-through of Mitsuba's
 *   `mask` is then not a bounce, as the format says.
 * - materials: each plugin's own `mitsuba` entry (src/materials/<kind>/kind.ts,
 *   through the registry), one-sided as the format says for spheres and the
 *   ground (Mitsuba's default); on meshes wrapped in `twosided` unless the
 *   material is a solid's boundary.
 * - textures: baked into float images (mitsubaTextures.ts) named by
 *   `texturePath`, which the caller writes (`textures` of exportMitsuba);
 *   the BSDF inside Mitsuba's `normalmap`, `twosided` and `mask` adapters
 *   (the registry's materialBsdf). On the ground, `to_uv` first turns the
 *   rectangle's coordinates into the format's (u, v) = (x, z).
 * - emission: an `area` emitter on the shape (its radiance a baked texture
 *   where the color is one), times a constant opacity (see areaEmitter).
 * - environment map: `envmap` with scale = intensity, rotated about +y; the
 *   file name as `environmentMapPath` gives it (default: as in the scene).
 * - meshes: a `ply` shape per mesh whose file `meshPath(i)` names: the
 *   caller writes it with `meshPlyFile` (world-space triangles, vertex
 *   normals when smooth; `face_normals` when flat, since Mitsuba would
 *   otherwise smooth them).
 * - lights: each kind's own `mitsuba` entry (src/lights/<kind>/kind.ts):
 *   sphere lights a `sphere` with an `area` emitter (one-sided, emitting
 *   along the outward normal: the format's "all outward directions") and a
 *   black `diffuse` BSDF (lights reflect nothing); every other kind as its
 *   plugin exports it (src/lights/<kind>/: Mitsuba's shape with an `area`
 *   emitter, or its emitter of the same name).
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
import { lightExtent, lightMitsuba } from '../lights/registry';
import type { MitsubaTextures } from '../materials/kind';
import { kindOf, materialBsdf, materialSeeThrough, meshBsdf } from '../materials/registry';
import { el, float, integer, num, point, rgb, serializeXml, str, triple, type XmlNode } from './mitsubaXml';
import { MitsubaTextureBaker, type BakedTexture } from './mitsubaTextures';
import type { TextureImage } from './texture/image';
import { isTexture } from './texture/texture';
import type { Camera, Material, Mesh, Scene as SceneModel, TriangleMesh, Vec3 } from './types';
import { asRenderScene, type RenderScene as Scene } from './fileMaterials';

export { bakedTextureFile, type BakedTexture } from './mitsubaTextures';

export { escapeXml } from './mitsubaXml';

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
  /** The scene's decoded texture images by name as written (SceneAssets.images). Required when a material has a texture. */
  images?: ReadonlyMap<string, TextureImage>;
  /** The file name to write for a baked texture (`BakedTexture.name`, e.g. resolved beside the XML). Default: the name. */
  texturePath?: (name: string) => string;
}

/** An export: the XML, and the baked texture images it names, which the caller writes (`bakedTextureFile`) where `texturePath` says. */
export interface MitsubaExport {
  xml: string;
  textures: BakedTexture[];
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

function scale3(v: Vec3, s: number): Vec3 {
  return [v[0] * s, v[1] * s, v[2] * s];
}

function isBlack(v: Vec3): boolean {
  return v[0] === 0 && v[1] === 0 && v[2] === 0;
}

function sensor(camera: Camera, width: number, height: number, spp: number, seed: number, farClip: number): XmlNode {
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

/**
 * The `area` emitter of an emissive material, if any; a textured emission's
 * radiance is its baked texture (times color x intensity). Mitsuba adds an
 * emitter's radiance at every hit, also where `mask` then lets the ray
 * through, while the format sees emission with probability `opacity`: a
 * constant opacity multiplies the radiance. (A textured opacity cannot be
 * multiplied into it: there the export counts the emission in full.)
 */
function areaEmitter(material: Material, textures: MitsubaTextures): XmlNode[] {
  const e = material.emission;
  if (!e) return [];
  const opacity = kindOf(material).opacity?.(material) ?? 1;
  const radiance = scale3(e.color, e.intensity * (isTexture(opacity) ? 1 : opacity));
  if (isBlack(radiance)) return [];
  const value = e.texture ? textures.bitmap('radiance', { ...e.texture, scale: radiance }, 'color') : rgb('radiance', radiance);
  return [el('emitter', { type: 'area' }, [value])];
}

function environmentEmitter(scene: Scene, opts: MitsubaExportOptions): XmlNode | null {
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

function groundShape(scene: Scene, baker: MitsubaTextureBaker): XmlNode | null {
  if (!scene.ground) return null;
  const [cx, , cz] = scene.camera.position;
  return el('shape', { type: 'rectangle' }, [
    el('transform', { name: 'to_world' }, [
      el('scale', { value: num(MITSUBA_GROUND_SIZE / 2) }),
      // Rotating -90 degrees about x maps the rectangle's normal +z to +y.
      el('rotate', { x: '1', angle: '-90' }),
      el('translate', { value: triple([cx, scene.ground.height, cz]) }),
    ]),
    materialBsdf(scene.ground.material, baker.forMaterial('ground.material', groundUv(cx, cz))),
  ]);
}

/**
 * The to_uv elements that turn the ground rectangle's Mitsuba coordinates
 * into the format's (u, v) = (x, z): the rectangle maps its [-1, 1]^2 to
 * uv = ((p + 1) / 2) before to_world, so with the scale, the rotation and
 * the translation of groundShape, x = cx + G (u_m - 1/2) and z = cz - G (v_m
 * - 1/2) (G the side). Mitsuba computes u_m in float, so (x, z) are off by
 * up to about G * 2^-24 * 2 (5e-3 units), as in the references.
 */
function groundUv(cx: number, cz: number): XmlNode[] {
  const side = MITSUBA_GROUND_SIZE;
  return [
    el('scale', { x: num(side), y: num(-side) }),
    el('translate', { x: num(cx - side / 2), y: num(cz + side / 2) }),
  ];
}

/** Every material of the scene (ground, spheres, meshes). */
function sceneMaterials(scene: Scene): Material[] {
  return [...(scene.ground ? [scene.ground.material] : []), ...scene.spheres.map((s) => s.material), ...scene.meshes.map((m) => m.material)];
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
  for (const l of scene.lights) {
    const e = lightExtent(l);
    if (e) extent = Math.max(extent, dist(e.center) + e.radius);
  }
  return Math.max(MITSUBA_DEFAULT_FAR_CLIP, 2 * extent);
}

/**
 * A Mitsuba 3 XML scene that renders, on average, the image the format
 * defines (a textured scene needs the baked images: use exportMitsuba).
 */
export function toMitsubaXml(scene: Scene | SceneModel, opts: MitsubaExportOptions = {}): string {
  return exportMitsuba(scene, opts).xml;
}



/** A Mitsuba 3 XML scene that renders, on average, the image the format defines, and the texture images it names. */
export function exportMitsuba(sceneModel: Scene | SceneModel, opts: MitsubaExportOptions = {}): MitsubaExport {
  const scene = asRenderScene(sceneModel, 'exportMitsuba');
  const width = opts.width ?? scene.image.width;
  const height = opts.height ?? scene.image.height;
  const spp = opts.spp ?? MITSUBA_DEFAULT_SPP;
  const seed = opts.seed ?? 0;
  const maxDepth = scene.render.maxBounces + 1;
  const baker = new MitsubaTextureBaker(opts.images, opts.texturePath);
  const integrator = sceneMaterials(scene).some(materialSeeThrough) ? 'volpath' : 'path';

  const children: XmlNode[] = [
    el('integrator', { type: integrator }, [integer('max_depth', maxDepth), integer('rr_depth', maxDepth + 1)]),
    sensor(scene.camera, width, height, spp, seed, farClip(scene)),
  ];
  const env = environmentEmitter(scene, opts);
  if (env) children.push(env);
  const ground = groundShape(scene, baker);
  if (ground) children.push(ground);
  for (const light of scene.lights) children.push(lightMitsuba(light));
  scene.spheres.forEach((sphere, i) => {
    children.push(
      el('shape', { type: 'sphere' }, [
        point('center', sphere.center),
        float('radius', sphere.radius),
        materialBsdf(sphere.material, baker.forMaterial(`spheres[${i}].material`)),
        ...areaEmitter(sphere.material, baker.forMaterial(`spheres[${i}].material.emission`)),
      ]),
    );
  });
  scene.meshes.forEach((mesh, i) => {
    if (!opts.meshPath) throw new Error('toMitsubaXml: the scene has meshes; pass meshPath and write meshPlyFile for each');
    const textures = baker.forMaterial(`meshes[${i}].material`);
    const bsdf = meshBsdf(mesh.material, textures);
    children.push(
      el('shape', { type: 'ply' }, [
        str('filename', opts.meshPath(i)),
        el('boolean', { name: 'face_normals', value: String(!(opts.meshSmooth?.(i) ?? true)) }),
        bsdf,
        ...areaEmitter(mesh.material, textures),
      ]),
    );
  });

  const out = ['<?xml version="1.0" encoding="utf-8"?>', `<!-- Exported by pathtrace from scene format version ${scene.version}. -->`];
  serializeXml(el('scene', { version: '3.0.0' }, children), 0, out);
  return { xml: out.join('\n') + '\n', textures: baker.baked };
}
