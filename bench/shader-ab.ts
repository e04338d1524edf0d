/**
 * A/B of trace-shader variants in one Chromium, interleaved to cancel the
 * machine's load swings: path rate per CPU second of the GPU process (median
 * of alternating runs), compile+first-draw time, and optionally relMSE vs the
 * reference at fixed spp (a bias check). Each variant is a directory holding
 * a copy of src/shaders (default: the working tree's), optionally with text
 * patches applied (PATCHES below); the page's trace fragment shader is
 * replaced by the variant's text at shaderSource() time, so no rebuild of the
 * page is needed (but dist/web must exist: npx vite build).
 *   npx tsx bench/shader-ab.ts --variants base=src/shaders,noShadow=src/shaders+noShadow [--scene seed] [--size 512x384] [--rounds 5] [--seconds 2] [--spp 0] [--seeds 2]
 * A variant may also be a whole trace shader (a path ending in .frag), and
 * DUMP_VARIANT=SPEC prints a variant's assembled text instead of running
 * (with DUMP_FEATURES='{"HAS_MESHES":1,...}' for other feature switches than the seed scene's).
 * The feature switches of a run are the page's own for --scene.
 */
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { readSceneFiles } from '../src/node/sceneFiles';
import { relativeMse, type LinearImage } from '../src/node/imageMetrics';
import { openRenderSession, type LoadOptions } from '../src/node/session';
import { assembleChunks, featureDefines, sceneDefines, TRACE_CHUNK_NAMES } from '../src/render/shaderChunks';
import { buildShader } from '../src/render/gl/shaderSource';
import { BASE_FEATURES } from '../src/render/packScene';
import { parseSceneText } from '../src/scene/schema';
import { decodePfm } from '../src/image/pfm';
import { projectRoot, renderFor } from './common';
import { downsample } from './run';


/** Named text edits for cost-share measurements: [search, replacement] pairs. */
const PATCHES: Record<string, [string | RegExp, string][]> = {
  // NEE's shadow ray loop removed (light always visible).
  noShadow: [['if (occluded(origin, light.direction, light.distance, light.skipSphere)) return vec3(0.0);', '']],
  // The whole NEE call removed.
  noNee: [['vec3 direct = sampleDirectLight(hit, frame, wo, material, uLight.xyz);', 'vec3 direct = vec3(0.0);']],
  // BSDF evaluation in NEE replaced by a constant.
  noNeeEval: [['vec3 f = bsdfEval(m, wo, wi, bsdfPdf);', 'vec3 f = vec3(wi.z); bsdfPdf = wi.z;']],
  // BSDF sampling replaced by a trivial cosine-ish direction.
  noBsdfSample: [['BsdfSample bs = sampleGuided(material, frame, wo, uBsdf, uLight.w);',
    'BsdfSample bs = BsdfSample(normalize(vec3(uBsdf.xy - 0.5, 1.0)), material.color, 1.0, false, true);']],
  // Light-cone construction + cone sampling replaced by the axis.
  noCone: [['vec3 wi = basisAround(cone.axis) * sampleUniformCone(u, cone.oneMinusCosMax);', 'vec3 wi = cone.axis;']],
  // RNG hashing replaced by a cheap non-random function.
  noRng: [[/uvec4 h = pcg4d\(uvec4\(rngPixelKey, rngSampleIndex, rngDimension\)\);/, 'uvec4 h = uvec4(rngPixelKey, rngSampleIndex, rngDimension) * 2654435761u;']],
  // Closest-hit loop over spheres removed (lights and ground remain).
  noSphereHit: [['for (int i = 0; i < sphereCount(); i++) {\n    float t = sphereHitT(', 'for (int i = 0; i < 0; i++) {\n    float t = sphereHitT(']],
  // Scene fetch cost: sphere geometry from arithmetic instead of the scene data (wrong image).
  fakeFetch: [[/vec4 sphereGeometry\(int i\) \{[^\n]*\}/,
    'vec4 sphereGeometry(int i) { float f = float(i); return vec4(f - 2.0, 0.5 + 0.1 * f, 0.3 * f, 0.5); }']],
  // Caustic guiding compiled out (as for a scene without guides).
  noGuide: [['#if CAUSTIC_GUIDES > 0', '#if 0']],
  // Caustic guide without the fixed-point step towards the reflection point.
  noGuideStep: [['  h = normalize(normalize(x - p) + normalize(light.xyz - p));\n  p = mirror.xyz + mirror.w * h;\n', '']],
  // Version 3 cost shares (lights.json and the principled scenes):
  // NEE removed.
  noNee3: [['vec3 direct = sampleDirectLight(hit, frame, wo, bsdf, shading, uLight.xyz);', 'vec3 direct = vec3(0.0);']],
  // NEE's shadow query removed (every sample visible).
  noShadow3: [['float transmitted = shadowTransmittance(origin, light.direction, light.distance, light.skipSphere);', 'float transmitted = 1.0;']],
  // The planar lights left out of closest-hit queries (wrong image: cost share).
  noPlanarClosest: [['vec2 range = planarCandidates(origin, direction, hit.t);', 'vec2 range = vec2(1e4, -1.0);']],
  // NEE's BSDF evaluation replaced by Lambert's.
  lambertNeeEval: [['vec3 f = bsdfEval(bsdf, wo, wi, bsdfPdf) * normalMapFactor(shading, light.direction);', 'vec3 f = vec3(max(wi.z, 0.0) / PI); bsdfPdf = max(wi.z, 0.0) / PI;']],
  // Light sampling: every emitter taken as the first one (no alias-table fetch or kind dispatch beyond it).
  firstEmitter: [['Emitter e = loadEmitter(keep ? slot : choice.alias);', 'Emitter e = loadEmitter(0);']],
  // The rectangle by area only (no spherical-rectangle sampling).
  rectangleByArea: [['bool rectangleBySolidAngle(float omega) { return omega > RECTANGLE_MIN_SOLID_ANGLE && omega < RECTANGLE_MAX_SOLID_ANGLE; }', 'bool rectangleBySolidAngle(float omega) { return false; }']],
  // Only the rectangle's and the sphere's samples compiled into the dispatch (wrong image: cost share of the other kinds).
  onlyRectangleSample: [[/  if \(e\.kind == EMITTER_(DISK|POINT|SPOT|DIRECTIONAL)\) s = \w+LightSample\(e, x, u\);\n/g, '']],
  // Each light kind's sample in a 0/1-trip loop, skipped when no lane of the quad picked that kind
  // (lights.json, 2026-12-02: 0.92x, the loops cost more than the samples they skip).
  loopDispatch: [[/  if \(e\.kind == (EMITTER_\w+)\) s = (\w+LightSample)\(e, x, u\);/g, '  for (int k = 0; k < (e.kind == $1 ? 1 : 0); k++) s = $2(e, x, u);']],
  // Only the rectangle's sample (the costliest) in a 0/1-trip loop (lights.json, 2026-12-02: 0.96x).
  loopRectangle: [['  if (e.kind == EMITTER_RECTANGLE) s = rectangleLightSample(e, x, u);', '  for (int k = 0; k < (e.kind == EMITTER_RECTANGLE ? 1 : 0); k++) s = rectangleLightSample(e, x, u);']],
  // The camera: a fixed direction per pixel.
  noCamera: [[/void generateCameraRay\(vec2 pixel, out vec3 origin, out vec3 direction\) \{/,
    'void generateCameraRay(vec2 pixel, out vec3 origin, out vec3 direction) { origin = uCameraPosition; direction = normalize(vec3(pixel / uResolution - 0.5, -1.0)); return; }\nvoid unusedCameraRay(vec2 pixel, out vec3 origin, out vec3 direction) {']],
};



function option(argv: string[], name: string, fallback: string): string {
  const i = argv.indexOf(`--${name}`);
  return i >= 0 && i + 1 < argv.length ? argv[i + 1] : fallback;
}

const median = (v: number[]) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];
const mean = (v: number[]) => v.reduce((a, b) => a + b, 0) / v.length;

/** Feature switches of the trace program (featureDefines' keys); default: the seed scene's. */
type Features = Record<string, number>;
const SEED_FEATURES: Features = featureDefines({ ...BASE_FEATURES, guides: 1 });

function variantSource(spec: string, root: URL, features: Features = SEED_FEATURES): string {
  if (spec.endsWith('.frag')) return readFileSync(spec, 'utf8'); // a whole trace shader, e.g. a hand-edited dump
  const [dir, ...patches] = spec.split('+');
  const base = new URL(dir.endsWith('/') ? dir : `${dir}/`, root);
  // The generated chunks come from this build; every other chunk from the variant's directory.
  const chunks = assembleChunks(TRACE_CHUNK_NAMES, (name) => readFileSync(new URL(name, base), 'utf8'));
  const defines = { ...sceneDefines(), ...features };
  let text = buildShader(chunks, defines).text;
  for (const p of patches) {
    const edits = PATCHES[p];
    if (!edits) throw new Error(`unknown patch ${p}`);
    for (const [search, replacement] of edits) {
      const before = text;
      text = text.replace(search, replacement);
      if (text === before) throw new Error(`patch ${p}: pattern not found: ${String(search)}`);
    }
  }
  return text;
}

async function main(argv: string[]): Promise<void> {
  const root = projectRoot();
  const sceneName = option(argv, 'scene', 'seed');
  const [w, h] = option(argv, 'size', '512x384').split('x').map(Number);
  const rounds = Number(option(argv, 'rounds', '5'));
  const seconds = Number(option(argv, 'seconds', '2'));
  const spp = Number(option(argv, 'spp', '0'));
  const seeds = Number(option(argv, 'seeds', '2'));
  const sceneFile = fileURLToPath(new URL(`test/fixtures/scenes/${sceneName}.json`, root));
  const scene = parseSceneText(readFileSync(sceneFile, 'utf8'));
  const { files } = await readSceneFiles(scene, sceneFile); // environment maps, meshes
  if (argv.includes('--bounces')) scene.render.maxBounces = Number(option(argv, 'bounces', '6'));

  const session = await openRenderSession();
  const page = session.page;
  await page.addInitScript(() => {
    const original = WebGL2RenderingContext.prototype.shaderSource;
    WebGL2RenderingContext.prototype.shaderSource = function (shader: WebGLShader, text: string) {
      const replacement = (window as unknown as { __traceSource?: string }).__traceSource;
      const isTrace = text.includes('uSamplesPerDraw') && text.includes('outSum');
      if (isTrace) (window as unknown as { __pageTraceSource?: string }).__pageTraceSource = text;
      if (replacement && isTrace) text = replacement;
      return original.call(this, shader, text);
    };
  });
  await page.reload();
  await page.waitForFunction(() => document.body.dataset.ready === 'true');
  // A fresh page per use: the renderer caches its programs by feature
  // switches, so a variant set on a page that compiled another would not compile.
  const use = async (text: string) => {
    await page.reload();
    await page.waitForFunction(() => document.body.dataset.ready === 'true');
    await page.evaluate((t) => ((window as unknown as { __traceSource?: string }).__traceSource = t), text);
  };
  // The feature switches the page compiles this scene with (its own trace program's defines).
  await session.load(scene, { width: 16, height: 16, seed: 1 } as LoadOptions, files);
  const pageText = await page.evaluate(() => (window as unknown as { __pageTraceSource?: string }).__pageTraceSource ?? '');
  const features: Features = {};
  for (const key of Object.keys(SEED_FEATURES)) {
    const m = new RegExp(`^#define ${key} (\\d+)$`, 'm').exec(pageText);
    if (!m) throw new Error(`the page's trace shader has no ${key}`);
    features[key] = Number(m[1]);
  }
  const same = variantSource('src/shaders', root, features) === pageText;
  console.log(`features: ${JSON.stringify(features)}; src/shaders assembled ${same ? 'equals' : 'DIFFERS FROM'} the page's trace shader`);
  const variants = option(argv, 'variants', 'base=src/shaders').split(',').map((v) => {
    const [name, spec] = v.split('=');
    return { name, text: variantSource(spec ?? name, spec?.startsWith('/') ? new URL('file:///') : root, features) };
  });

  try {
    const cpu = new Map<string, number[]>(variants.map((v) => [v.name, []]));
    const wall = new Map<string, number[]>(variants.map((v) => [v.name, []]));
    const compile = new Map<string, number[]>(variants.map((v) => [v.name, []]));
    for (let r = 0; r < rounds; r++) {
      for (const v of r % 2 ? [...variants].reverse() : variants) {
        await use(v.text);
        const t0 = performance.now();
        await session.load(scene, { width: w, height: h, seed: 1 + r } as LoadOptions, files);
        await session.render(1);
        compile.get(v.name)!.push((performance.now() - t0) / 1000);
        const run = await renderFor(session, seconds, 0.5);
        cpu.get(v.name)!.push((run.spp * w * h) / (run.cpuSeconds ?? NaN) / 1e6);
        wall.get(v.name)!.push((run.spp * w * h) / run.seconds / 1e6);
      }
    }
    const errors = new Map<string, number>();
    if (spp > 0) {
      const pfm = decodePfm(readFileSync(new URL(`test/fixtures/references/${sceneName}.pfm`, root)));
      const reference: LinearImage = { width: pfm.width, height: pfm.height, channels: 3, data: pfm.rgb };
      for (const v of variants) {
        await use(v.text);
        const e: number[] = [];
        for (let seed = 1; seed <= seeds; seed++) {
          await session.load(scene, { width: pfm.width, height: pfm.height, seed: 100 + seed } as LoadOptions, files);
          await session.render(spp);
          const image = { width: pfm.width, height: pfm.height, channels: 4, data: await session.readLinear() };
          e.push(relativeMse(downsample(image, 1), reference));
        }
        errors.set(v.name, mean(e));
      }
    }
    const base = median(cpu.get(variants[0].name)!);
    for (const v of variants) {
      const c = median(cpu.get(v.name)!);
      console.log(
        `${v.name.padEnd(16)} ${c.toFixed(3)} Mpath/CPU-s (x${(c / base).toFixed(2)}; ms/spp ${((w * h) / c / 1e3).toFixed(1)}) ` +
          `runs ${cpu.get(v.name)!.map((x) => x.toFixed(2)).join(' ')} | wall ${median(wall.get(v.name)!).toFixed(3)} | ` +
          `compile+1spp ${median(compile.get(v.name)!).toFixed(2)} s (first ${compile.get(v.name)![0].toFixed(2)})` +
          (errors.has(v.name) ? ` | relMSE@${spp}spp ${errors.get(v.name)!.toExponential(3)}` : ''),
      );
    }
  } finally {
    await session.close();
  }
}

if (process.env.DUMP_VARIANT) { console.log(variantSource(process.env.DUMP_VARIANT, projectRoot(), process.env.DUMP_FEATURES ? (JSON.parse(process.env.DUMP_FEATURES) as Features) : SEED_FEATURES)); process.exit(0); }
main(process.argv.slice(2)).catch((error) => {
  console.error(error);
  process.exit(1);
});
