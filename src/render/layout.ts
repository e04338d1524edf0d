/**
 * The packed scene layout, defined once. `packScene` writes it and the
 * shaders read it through the #defines that `layoutDefines` generates.
 */
import { MAX_LIGHTS, MAX_SPHERES } from '../scene/limits';

/** vec4 slots of one sphere: [center.xyz, radius], [color.rgb, roughness]. */
export const SPHERE_FIELDS = { GEOMETRY: 0, MATERIAL: 1 } as const;
/** vec4 slots of one light: [position.xyz, radius], [radiance.rgb, 0]. */
export const LIGHT_FIELDS = { GEOMETRY: 0, RADIANCE: 1 } as const;
/** vec4 slots of the ground: [height, 0, 0, 0], [color.rgb, roughness]. */
export const GROUND_FIELDS = { GEOMETRY: 0, MATERIAL: 1 } as const;

export const SPHERE_VEC4S = Object.keys(SPHERE_FIELDS).length;
export const LIGHT_VEC4S = Object.keys(LIGHT_FIELDS).length;
export const GROUND_VEC4S = Object.keys(GROUND_FIELDS).length;

/** caustic_guide.glsl holds exactly two named cones: change both together. */
export const MAX_GUIDES = 2;
/** vec4 slots of one guide in the block: the mirror's and the light's [center.xyz, radius]. */
export const GUIDE_FIELDS = { MIRROR: 0, LIGHT: 1 } as const;
export const GUIDE_VEC4S = Object.keys(GUIDE_FIELDS).length;

/** vec4 offsets of the members of the std140 `SceneBlock` uniform block. */
export const BLOCK = {
  spheres: 0,
  lights: MAX_SPHERES * SPHERE_VEC4S,
  ground: MAX_SPHERES * SPHERE_VEC4S + MAX_LIGHTS * LIGHT_VEC4S,
  environment: MAX_SPHERES * SPHERE_VEC4S + MAX_LIGHTS * LIGHT_VEC4S + GROUND_VEC4S,
  counts: MAX_SPHERES * SPHERE_VEC4S + MAX_LIGHTS * LIGHT_VEC4S + GROUND_VEC4S + 1,
  guides: MAX_SPHERES * SPHERE_VEC4S + MAX_LIGHTS * LIGHT_VEC4S + GROUND_VEC4S + 2,
  size: MAX_SPHERES * SPHERE_VEC4S + MAX_LIGHTS * LIGHT_VEC4S + GROUND_VEC4S + 2 + MAX_GUIDES * GUIDE_VEC4S,
} as const;

/**
 * Caustic guiding (src/shaders/lights/caustic_guide.glsl): at most this many
 * (mirror sphere, light) pairs; the probability of drawing a rough vertex's
 * next direction towards a light's image in a mirror; how much wider than
 * the estimated image the cone is.
 */
export const GUIDE_PROBABILITY = 0.1;
export const GUIDE_MARGIN = 2.0;
/** A sphere is a guiding mirror when its specular lobe is a delta (as in material.glsl) and carries at least this weight. */
export const GUIDE_MIN_SPECULAR = 0.5;
/** material.glsl treats GGX lobes with alpha = r^2 below this as ideal mirrors. */
export const SMOOTH_ALPHA = 1e-3;

/** Tone mapping operators of the display pass, by name. */
export const TONEMAPS = ['none', 'aces', 'neutral', 'agx'] as const;
export type ToneMap = (typeof TONEMAPS)[number];

/**
 * Samples whose radiance is not below this are treated as invalid (NaN and
 * Inf fail the test too). The schema allows emission up to 1e12 * 1e12 =
 * 1e24, so valid samples stay far below; float32 sums of 1e30-sized samples
 * still hold 3e8 of them.
 */
export const MAX_RADIANCE = 1e30;

/**
 * Random-number dimensions (one rand4() each): the camera ray takes one, each
 * bounce three (light sample, whose .w picks a caustic guide; BSDF sample,
 * whose .w picks the technique; Russian roulette).
 */
export const RNG_CAMERA_DIMENSIONS = 1;
export const RNG_BOUNCE_DIMENSIONS = 3;

/**
 * Russian roulette (PathTracerOptions.russianRoulette, off by default): from
 * this many scattering events on, a path whose throughput fell below the
 * threshold survives with probability = its largest throughput component.
 */
export const ROULETTE_DEPTH = 3;
export const ROULETTE_THRESHOLD = 0.95;

/**
 * Generators of the R_d Kronecker sequence (M. Roberts, "The unreasonable
 * effectiveness of quasirandom sequences", 2018) for `n` coordinates:
 * alpha_j = frac(1 / phi^j), j = 1..n, phi the positive root of
 * x^(n+1) = x + 1; as 32-bit fixed point. The low-discrepancy sampler uses
 * six: camera jitter, first light sample, first BSDF sample (2D each).
 */
export function kroneckerGenerators(n: number): number[] {
  let phi = 2;
  for (let i = 0; i < 100; i++) phi = (1 + phi) ** (1 / (n + 1));
  return Array.from({ length: n }, (_, j) => Math.floor(((1 / phi ** (j + 1)) % 1) * 2 ** 32) >>> 0);
}

function ldGeneratorDefines(): Record<string, string> {
  const g = kroneckerGenerators(6);
  const pair = (i: number) => `uvec2(${g[2 * i]}u, ${g[2 * i + 1]}u)`;
  return { LD_GENERATOR_CAMERA: pair(0), LD_GENERATOR_LIGHT: pair(1), LD_GENERATOR_BSDF: pair(2) };
}

export type SamplerKind = 'kronecker' | 'independent';

export function layoutDefines(): Record<string, string | number> {
  return {
    MAX_SPHERES,
    MAX_LIGHTS,
    SPHERE_VEC4S,
    LIGHT_VEC4S,
    GROUND_VEC4S,
    SPHERE_GEOMETRY: SPHERE_FIELDS.GEOMETRY,
    SPHERE_MATERIAL: SPHERE_FIELDS.MATERIAL,
    LIGHT_GEOMETRY: LIGHT_FIELDS.GEOMETRY,
    LIGHT_RADIANCE: LIGHT_FIELDS.RADIANCE,
    GROUND_GEOMETRY: GROUND_FIELDS.GEOMETRY,
    GROUND_MATERIAL: GROUND_FIELDS.MATERIAL,
    BLOCK_SPHERES: BLOCK.spheres,
    MAX_GUIDES,
    GUIDE_VEC4S,
    GUIDE_MIRROR: GUIDE_FIELDS.MIRROR,
    GUIDE_LIGHT: GUIDE_FIELDS.LIGHT,
    GUIDE_PROBABILITY: GUIDE_PROBABILITY.toFixed(6),
    GUIDE_MARGIN: GUIDE_MARGIN.toFixed(6),
    SMOOTH_ALPHA: SMOOTH_ALPHA.toExponential(),
    BLOCK_LIGHTS: BLOCK.lights,
    MAX_RADIANCE: MAX_RADIANCE.toExponential(),
    RNG_CAMERA_DIMENSIONS: `${RNG_CAMERA_DIMENSIONS}u`,
    RNG_BOUNCE_DIMENSIONS: `${RNG_BOUNCE_DIMENSIONS}u`,
    ROULETTE_DEPTH,
    ROULETTE_THRESHOLD: ROULETTE_THRESHOLD.toFixed(6),
    ...ldGeneratorDefines(),
    LOW_DISCREPANCY: 1,
    ...Object.fromEntries(TONEMAPS.map((name, i) => [`TONEMAP_${name.toUpperCase()}`, i])),
  };
}
