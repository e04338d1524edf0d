/**
 * The light registry's packing and program variants: the emitter records
 * and planar-light records a scene with every kind packs into, the emitter
 * choice by power, and the switches that keep the code of the new kinds out
 * of programs for scenes without them.
 */
import { describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import { packScene } from '../render/packScene';
import { featureDefines } from '../render/shaderChunks';
import { EMITTER, HEADER, MATERIAL, PLANAR_LIGHT, SECTIONS } from '../render/layout/scene';
import { unpackMaterial } from '../materials/registry';
import { parseScene } from '../scene/schema';
import { EMITTER_KINDS, lightDispatchGlsl, lightPower, unpackEmitter } from './registry';
import { readRecord as read } from '../../test/support/records';
import { choiceEntry } from '../../test/support/lightChoice';

const lightsJson = JSON.parse(readFileSync(new URL('../../test/fixtures/scenes/lights.json', import.meta.url), 'utf8'));

const emitterAt = (data: Float32Array, i: number) => unpackEmitter(data.subarray((SECTIONS.emitters + i * EMITTER.texels) * 4, (SECTIONS.emitters + (i + 1) * EMITTER.texels) * 4));

describe('light registry: packing', () => {
  const scene = parseScene(lightsJson);
  const packed = packScene(scene);
  const header = read(packed.block, 0, HEADER, 0);

  it('packs every light after version 2 emitters, picked half by power and half uniformly (the scene has delta lights)', () => {
    expect(packed.features.lights).toEqual(['rectangle', 'disk', 'point', 'spot', 'directional']);
    expect(header).toMatchObject({ sphereCount: 3, emitterCount: 5, planarLightCount: 2 });
    const emitters = [0, 1, 2, 3, 4].map((i) => emitterAt(packed.data, i));
    expect(emitters.map((e) => e.type)).toEqual(['rectangle', 'disk', 'point', 'spot', 'directional']);
    expect(emitters.map((e) => e.kind)).toEqual(['rectangle', 'disk', 'point', 'spot', 'directional'].map((t) => EMITTER_KINDS[t]));
    expect(emitters.map((e) => e.primitive)).toEqual([0, 1, -1, -1, -1]);
    // The global table (points outside the grid of render/lightChoice.ts).
    const pdfs = emitters.map((_, i) => choiceEntry(packed, i).pdf);
    const total = pdfs.reduce((sum, p) => sum + p, 0);
    expect(total).toBeCloseTo(1, 6);
    // Each pdf is half its power share plus half of 1/5: the shares' ratio is
    // the powers' (the rectangle's against the point's, neither depends on the bounds).
    const bounds = { radius: 1 };
    const ratio = lightPower(scene.lights[0], bounds) / lightPower(scene.lights[2], bounds);
    expect((pdfs[0] - 0.1) / (pdfs[2] - 0.1)).toBeCloseTo(ratio, 4);
    pdfs.forEach((p) => expect(p).toBeGreaterThan(0.1));
    expect(emitters[2]).toMatchObject({ radiance: [3, 3, 3], position: [0, expect.closeTo(1.4, 6), expect.closeTo(1.6, 6)] });
    const spot = emitters[3];
    expect(spot.cosCutoff).toBeCloseTo(Math.cos((25 * Math.PI) / 180), 6);
    expect(spot.cosBeam).toBeCloseTo(Math.cos((15 * Math.PI) / 180), 6);
    expect(Math.hypot(...(spot.axis as number[]))).toBeCloseTo(1, 6);
    expect(Math.hypot(...(emitters[4].direction as number[]))).toBeCloseTo(1, 6);
  });

  it('writes the rectangle and disk into the planar-light table with emitter-only materials and their emitter slots', () => {
    for (const i of [0, 1]) {
      const planar = read(packed.data, SECTIONS.planarLights, PLANAR_LIGHT, i);
      expect(planar.kind).toBe(EMITTER_KINDS[scene.lights[i].type]);
      expect(planar.emitter).toBe(i);
      const base = (SECTIONS.materials + (planar.material as number) * MATERIAL.texels) * 4;
      const material = unpackMaterial(packed.data.subarray(base, base + MATERIAL.texels * 4));
      const l = scene.lights[i] as { color: number[]; intensity: number };
      expect(material.type).toBe('emitterOnly');
      (material.emission as number[]).forEach((c, k) => expect(c).toBeCloseTo(l.color[k] * l.intensity, 5));
    }
    const rect = read(packed.data, SECTIONS.planarLights, PLANAR_LIGHT, 0);
    // Rotated 25 degrees about z: u = (cos, sin, 0) * w/2.
    expect((rect.u as number[])[0]).toBeCloseTo(0.6 * Math.cos((25 * Math.PI) / 180), 6);
    expect((rect.u as number[])[1]).toBeCloseTo(0.6 * Math.sin((25 * Math.PI) / 180), 6);
  });

  it('keeps the new kinds out of the program of a scene without them', () => {
    const v1 = packScene(parseScene({ camera: { position: [0, 1, 5], target: [0, 0, 0] }, lights: [{ position: [0, 3, 0], radius: 0.5 }] }));
    expect(v1.features.lights).toEqual([]);
    const defines = featureDefines(v1.features);
    expect(defines).toMatchObject({
      HAS_RECTANGLE_LIGHT: 0, HAS_DISK_LIGHT: 0, HAS_POINT_LIGHT: 0, HAS_SPOT_LIGHT: 0, HAS_DIRECTIONAL_LIGHT: 0, HAS_PLANAR_LIGHTS: 0,
      // The sphere's record: version 2's three texels.
      EMITTER_FETCHED_TEXELS: 3,
    });
    expect(featureDefines(packed.features)).toMatchObject({ HAS_SPOT_LIGHT: 1, HAS_PLANAR_LIGHTS: 1, EMITTER_FETCHED_TEXELS: EMITTER.texels });
    // Every kind's call in the dispatch is behind its switch.
    const dispatch = lightDispatchGlsl();
    for (const type of ['rectangle', 'disk', 'point', 'spot', 'directional']) expect(dispatch).toMatch(new RegExp(`#if HAS_${type.toUpperCase()}_LIGHT\\n  if \\([^)]*\\) (s = |return )${type}Light`));
  });
});
