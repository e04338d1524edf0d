/**
 * The page's material edits as pure functions: switching the type and
 * setting the emitted intensity. Every result must be a valid scene
 * material (checked by parsing a scene that uses it).
 */
import { describe, expect, it } from 'vitest';
import { switchMaterialType, withEmissionIntensity } from '../../src/app/materialControls';
import { parseScene } from '../../src/scene/schema';
import { serializeScene } from '../../src/scene/serialize';
import type { Material, Scene } from '../../src/scene/types';

const red: Material = { type: 'standard', color: [0.8, 0.1, 0.1], roughness: 0.3 };
const tintedGlass: Material = { type: 'dielectric', color: [0.7, 0.9, 1], roughness: 0.2, ior: 1.33 };

/** Parses a one-sphere scene with `material` (throws, naming the field, if it is invalid). */
function sceneWith(material: Material): Scene {
  return parseScene({
    version: 2,
    camera: { position: [0, 1, 5], target: [0, 1, 0] },
    spheres: [{ center: [0, 1, 0], radius: 1, material }],
  });
}

describe('switchMaterialType', () => {
  it('turns a standard material into clear smooth glass of ior 1.5, keeping emission', () => {
    const glowing: Material = { ...structuredClone(red), emission: { color: [1, 0.5, 0.2], intensity: 4 } };
    const glass = switchMaterialType(glowing, 'dielectric');
    expect(glass).toEqual({ type: 'dielectric', color: [1, 1, 1], roughness: 0, ior: 1.5, emission: { color: [1, 0.5, 0.2], intensity: 4 } });
    expect(sceneWith(glass).spheres[0].material).toEqual(glass);
    expect(glowing.type).toBe('standard'); // the input is not changed
  });

  it('turns glass into a standard material with the tint as color and the same roughness, no ior', () => {
    const standard = switchMaterialType(tintedGlass, 'standard');
    expect(standard).toEqual({ type: 'standard', color: [0.7, 0.9, 1], roughness: 0.2 });
    expect('ior' in standard).toBe(false);
    expect(sceneWith(standard).spheres[0].material).toEqual(standard);
  });

  it('brings back the remembered material of the target type, with the current emission', () => {
    const emission = { color: [0, 1, 0] as [number, number, number], intensity: 2 };
    const rememberedWithOtherEmission: Material = { ...structuredClone(red), emission: { color: [1, 1, 1], intensity: 9 } };
    const back = switchMaterialType({ ...structuredClone(tintedGlass), emission }, 'standard', rememberedWithOtherEmission);
    expect(back).toEqual({ type: 'standard', color: [0.8, 0.1, 0.1], roughness: 0.3, emission });
    const noEmission = switchMaterialType(tintedGlass, 'standard', rememberedWithOtherEmission);
    expect(noEmission).toEqual(red);
    expect(switchMaterialType(red, 'dielectric', tintedGlass)).toEqual(tintedGlass);
  });

  it('ignores a remembered material of another type and returns a copy when the type does not change', () => {
    expect(switchMaterialType(red, 'dielectric', red)).toMatchObject({ type: 'dielectric', ior: 1.5 });
    const same = switchMaterialType(red, 'standard');
    expect(same).toEqual(red);
    expect(same).not.toBe(red);
    expect((same as typeof red).color).not.toBe(red.color);
  });

  it('makes a version-2 scene out of a version-1 one; switching back makes it version 1 again', () => {
    const scene = sceneWith(structuredClone(red));
    scene.version = 1;
    scene.spheres[0].material = switchMaterialType(scene.spheres[0].material, 'dielectric');
    expect(serializeScene(scene).version).toBe(2);
    scene.spheres[0].material = switchMaterialType(scene.spheres[0].material, 'standard', red);
    expect(serializeScene(scene).version).toBe(1);
  });
});

describe('switchMaterialType from textures', () => {
  it('leaves a textured color and roughness behind: the other kinds take constants', () => {
    const texture = { image: 'r.png', channel: 'r' as const, scale: 1, uv: { offset: [0, 0] as [number, number], scale: [1, 1] as [number, number], rotation: 0 } };
    const textured = { type: 'principled', baseColor: texture, roughness: texture, metallic: 0, ior: 1.5, specTint: 0, specTrans: 0, sheen: 0, sheenTint: 0, clearcoat: 0, clearcoatGloss: 0, opacity: 1 } as unknown as Material;
    const standard = switchMaterialType(textured, 'standard');
    expect(standard).toEqual({ type: 'standard', color: [0.8, 0.8, 0.8], roughness: 1 });
    expect(sceneWith(standard).spheres[0].material).toEqual(standard);
  });
});

describe('withEmissionIntensity', () => {
  it('adds emission with the given color when the intensity becomes positive', () => {
    const m = structuredClone(red);
    withEmissionIntensity(m, 3, [1, 0.5, 0]);
    expect(m.emission).toEqual({ color: [1, 0.5, 0], intensity: 3 });
    expect(sceneWith(m).spheres[0].material.emission).toEqual({ color: [1, 0.5, 0], intensity: 3 });
  });

  it('changes only the intensity of existing emission', () => {
    const m: Material = { ...structuredClone(tintedGlass), emission: { color: [0.2, 0.3, 0.4], intensity: 1 } };
    withEmissionIntensity(m, 7, [1, 1, 1]);
    expect(m.emission).toEqual({ color: [0.2, 0.3, 0.4], intensity: 7 });
  });

  it('removes the emission key at 0 (and for anything not above 0), so the scene stays minimal', () => {
    for (const intensity of [0, -1, Number.NaN]) {
      const m: Material = { ...structuredClone(red), emission: { color: [1, 1, 1], intensity: 5 } };
      withEmissionIntensity(m, intensity, [1, 1, 1]);
      expect('emission' in m).toBe(false);
    }
    const scene = sceneWith(structuredClone(red));
    scene.version = 1;
    withEmissionIntensity(scene.spheres[0].material, 2, [1, 1, 1]);
    expect(serializeScene(scene).version).toBe(2);
    withEmissionIntensity(scene.spheres[0].material, 0, [1, 1, 1]);
    expect(serializeScene(scene).version).toBe(1);
    expect(JSON.stringify(serializeScene(scene))).not.toContain('emission');
  });
});
