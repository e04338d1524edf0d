import { describe, expect, it } from 'vitest';
import { BLOCK, GROUND_FIELDS, GUIDE_FIELDS, LIGHT_FIELDS, LIGHT_VEC4S, MAX_GUIDES, SPHERE_FIELDS, SPHERE_VEC4S } from '../../src/render/layout';
import { causticGuides, packScene } from '../../src/render/packScene';
import { parseScene } from '../../src/scene/schema';

const camera = { position: [0, 1, 5], target: [0, 0, 0] };
const vec4 = (data: Float32Array, slot: number) => Array.from(data.subarray(slot * 4, slot * 4 + 4));

describe('packScene', () => {
  it('writes every field where layout.ts says, with light radiance = color * intensity', () => {
    const scene = parseScene({
      camera,
      environment: { color: [0.5, 0.25, 1], intensity: 2 },
      ground: { height: -1, material: { color: [0.1, 0.2, 0.3], roughness: 0.4 } },
      lights: [{ position: [1, 2, 3], radius: 0.5, color: [1, 0.5, 0.25], intensity: 4 }],
      spheres: [
        { center: [0, 0, 0], radius: 1, material: { color: [0.25, 0.5, 0.75], roughness: 0.5 } },
        { center: [3, 0, 0], radius: 2 },
      ],
    });
    const data = packScene(scene);
    expect(data.length).toBe(BLOCK.size * 4);
    expect(vec4(data, BLOCK.spheres + SPHERE_VEC4S + SPHERE_FIELDS.GEOMETRY)).toEqual([3, 0, 0, 2]);
    expect(vec4(data, BLOCK.spheres + SPHERE_FIELDS.MATERIAL)).toEqual([0.25, 0.5, 0.75, 0.5]);
    expect(vec4(data, BLOCK.lights + LIGHT_FIELDS.GEOMETRY)).toEqual([1, 2, 3, 0.5]);
    expect(vec4(data, BLOCK.lights + LIGHT_FIELDS.RADIANCE).slice(0, 3)).toEqual([4, 2, 1]);
    expect(vec4(data, BLOCK.ground + GROUND_FIELDS.GEOMETRY)[0]).toBe(-1);
    expect(vec4(data, BLOCK.environment).slice(0, 3)).toEqual([1, 0.5, 2]);
    expect(vec4(data, BLOCK.counts)).toEqual([2, 1, 1, 0]);
    expect(LIGHT_VEC4S).toBe(2);
  });

  it('packs an empty scene with zero counts and a black environment', () => {
    const data = packScene(parseScene({ camera }));
    expect(vec4(data, BLOCK.counts)).toEqual([0, 0, 0, 0]);
    expect(vec4(data, BLOCK.environment)).toEqual([0, 0, 0, 0]);
  });
});

describe('causticGuides', () => {
  const mirror = (x: number, radius = 1, roughness = 0) => ({ center: [x, 1, 0], radius, material: { color: [0.9, 0.9, 0.9], roughness } });
  const light = (intensity: number, radius = 0.5) => ({ position: [0, 5, 0], radius, intensity });

  it('pairs ideal mirrors (alpha below the smooth limit) with lights, brightest first, at most MAX_GUIDES', () => {
    const scene = parseScene({
      camera,
      lights: [light(10), light(40), light(0)],
      spheres: [mirror(0, 1, 0.5), mirror(2, 0.5, 0.02), mirror(-2, 1, 0), mirror(4, 1, 0.04)],
    });
    // Sphere 0 is rough, sphere 3 has alpha = 0.0016 (a glossy lobe, not a mirror), light 2 is dark.
    expect(causticGuides(scene)).toEqual([[2, 1], [1, 1]].slice(0, MAX_GUIDES));
    const packed = packScene(scene);
    expect(vec4(packed, BLOCK.counts)[3]).toBe(Math.min(MAX_GUIDES, 4));
    // Guide 0 = (sphere 2, light 1): their geometry.
    expect(vec4(packed, BLOCK.guides + GUIDE_FIELDS.MIRROR)).toEqual([-2, 1, 0, 1]);
    expect(vec4(packed, BLOCK.guides + GUIDE_FIELDS.LIGHT)).toEqual([0, 5, 0, 0.5]);
  });

  it('has no guides without mirrors or without lights', () => {
    expect(causticGuides(parseScene({ camera, lights: [light(10)], spheres: [mirror(0, 1, 1)] }))).toEqual([]);
    expect(causticGuides(parseScene({ camera, spheres: [mirror(0)] }))).toEqual([]);
  });
});
