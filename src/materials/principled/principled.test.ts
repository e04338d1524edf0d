/**
 * The principled material, as Mitsuba tests a plugin (test_principled.py):
 * its schema and export; its sampler against its pdf (chi-square over the
 * whole sphere, on the real GLSL, from outside and from inside the solid);
 * and its sample weights against Mitsuba's own directional albedo of the
 * exported BSDF (the furnace values of
 * test/fixtures/furnace-principled/cases.json, made by
 * scripts/make-principled-furnace.ts). principled.json against its Mitsuba
 * reference is in test/browser/references.test.ts with the other scenes.
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { MATERIAL_TEXELS, materialSchema, normalizeMaterial, packMaterial, unpackMaterial, type Material } from '../registry';
import { toMitsubaXml } from '../../scene/mitsuba';
import { parseScene, safeParseScene } from '../../scene/schema';
import { serializeScene } from '../../scene/serialize';
import type { Vec3 } from '../../scene/types';
import { useRenderSession } from '../../../test/support/browser';
import { bsdfWeights, samplerChiSquare } from '../../../test/support/bsdfKernels';
import type { PrincipledMaterial } from './kind';

const camera = { position: [0, 0, 4], target: [0, 0, 0] };
const sceneWith = (material: unknown, version = 3) => ({ version, camera, spheres: [{ center: [0, 0, 0], radius: 1, material }] });
const principled = (input: Record<string, unknown>) =>
  normalizeMaterial(materialSchema('principled')!.parse({ type: 'principled', ...input }) as Record<string, unknown>) as PrincipledMaterial;

describe('principled: schema, serialization, export, record', () => {
  it("defaults to Mitsuba's parameters except base color 0.8", () => {
    const m = parseScene(sceneWith({ type: 'principled' })).spheres[0].material;
    expect(m).toEqual({
      type: 'principled',
      baseColor: [0.8, 0.8, 0.8],
      metallic: 0,
      roughness: 0.5,
      ior: 1.5,
      specTint: 0,
      specTrans: 0,
      sheen: 0,
      sheenTint: 0,
      clearcoat: 0,
      clearcoatGloss: 0,
      opacity: 1,
    });
  });

  it('round-trips through the serializer, as version 3', () => {
    const scene = parseScene(sceneWith({ type: 'principled', baseColor: '#c0392b', metallic: 0.3, roughness: 0.2, ior: 1.33, specTint: 0.5, specTrans: 0.25, sheen: 1, sheenTint: 0.5, clearcoat: 0.7, clearcoatGloss: 0.9, emission: { color: [1, 0.5, 0], intensity: 2 } }));
    expect(parseScene(serializeScene(scene))).toEqual(scene);
    expect(serializeScene(scene).version).toBe(3);
  });

  it.each([
    [{ type: 'principled', metallic: 1.5 }, 'spheres[0].material.metallic', 'must be <= 1'],
    [{ type: 'principled', sheen: -0.1 }, 'spheres[0].material.sheen', 'must be >= 0'],
    [{ type: 'principled', ior: 1 }, 'spheres[0].material.ior', 'must be >= 1.01'],
    [{ type: 'principled', ior: 4.5 }, 'spheres[0].material.ior', 'must be <= 4'],
    [{ type: 'principled', baseColor: [0.5, 2, 0.5] }, 'spheres[0].material.baseColor[1]', 'must be <= 1'],
    [{ type: 'principled', opacity: 1.5 }, 'spheres[0].material.opacity', '<= 1'],
    [{ type: 'principled', roughness: { image: 'r.png', channel: 'x' } }, 'spheres[0].material.roughness.channel', 'must be "r" or "g" or "b" or "a"'],
    [{ type: 'principled', baseColor: { image: 'c.png', channel: 'g' } }, 'spheres[0].material.baseColor.channel', 'unknown key'],
    [{ type: 'principled', metallic: { image: 'm.png', cutoff: 2 } }, 'spheres[0].material.metallic.cutoff', '<= 1'],
    [{ type: 'principled', roughness: { image: '' } }, 'spheres[0].material.roughness.image', 'must name a file'],
    [{ type: 'principled', normalMap: 0.5 }, 'spheres[0].material.normalMap', ''],
    [{ type: 'principled', ior: { image: 'i.png' } }, 'spheres[0].material.ior', ''],
    [{ type: 'principled', color: [1, 1, 1] }, 'spheres[0].material.color', 'unknown key for this type'],
  ])('rejects %j at its key', (material, path, message) => {
    const result = safeParseScene(sceneWith(material));
    expect(result.ok).toBe(false);
    if (!result.ok) expect(result.issues).toContainEqual({ path, message: expect.stringContaining(message) });
  });

  it('needs version 3; opaque on the ground, but not transmitting', () => {
    const result = safeParseScene(sceneWith({ type: 'principled' }, 2));
    expect(result.ok).toBe(false);
    if (!result.ok) expect(result.issues).toContainEqual({ path: 'spheres[0].material.type', message: 'requires "version": 3' });
    expect(parseScene({ version: 3, camera, ground: { material: { type: 'principled', roughness: 0.7 } } }).ground?.material.type).toBe('principled');
    const glass = safeParseScene({ version: 3, camera, ground: { material: { type: 'principled', specTrans: 0.1 } } });
    expect(glass.ok).toBe(false);
    if (!glass.ok) expect(glass.issues).toContainEqual({ path: 'ground.material.type', message: expect.stringContaining('"principled" with specTrans above 0') });
  });

  it("exports Mitsuba's principled with every parameter, two-sided on meshes only when opaque", () => {
    const scene = parseScene({
      version: 3,
      camera,
      spheres: [{ center: [0, 0, 0], radius: 1, material: { type: 'principled', baseColor: [1, 0.5, 0.25], metallic: 0.1, roughness: 0.2, ior: 1.45, specTint: 0.3, specTrans: 0.4, sheen: 0.5, sheenTint: 0.6, clearcoat: 0.7, clearcoatGloss: 0.8 } }],
      meshes: [
        { file: 'a.obj', material: { type: 'principled' } },
        { file: 'b.obj', material: { type: 'principled', specTrans: 1 } },
      ],
    });
    const xml = toMitsubaXml(scene, { meshPath: (m) => `${m}.ply` });
    const values = ['<rgb name="base_color" value="1, 0.5, 0.25"/>', 'metallic" value="0.1"', 'roughness" value="0.2"', 'eta" value="1.45"', 'spec_tint" value="0.3"', 'spec_trans" value="0.4"', 'sheen" value="0.5"', 'sheen_tint" value="0.6"', 'clearcoat" value="0.7"', 'clearcoat_gloss" value="0.8"'];
    for (const v of values) expect(xml).toContain(v);
    expect(xml).toMatch(/<bsdf type="twosided">\s*<bsdf type="principled">\s*<rgb name="base_color" value="0.8, 0.8, 0.8"\/>/);
    expect(xml.match(/<bsdf type="twosided">/g)).toHaveLength(1);
    expect(xml.match(/<bsdf type="principled">/g)).toHaveLength(3);
  });

  it('packs baseColor and the nine scalars into texels 1 to 3, the opacity and texture indices after them', () => {
    expect(MATERIAL_TEXELS).toBe(7);
    const m = principled({ baseColor: [0.1, 0.2, 0.3], metallic: 0.4, roughness: 0.5, ior: 1.6, specTint: 0.7, specTrans: 0.8, sheen: 0.9, sheenTint: 0.25, clearcoat: 0.75, clearcoatGloss: 0.125 });
    const record = packMaterial(m, true);
    expect(Array.from(record.subarray(4, 16))).toEqual([0.1, 0.2, 0.3, 0.4, 0.5, 1.6, 0.7, 0.8, 0.9, 0.25, 0.75, 0.125].map(Math.fround));
    // Opacity 1, then no texture in any of the eight slots (the emission's last).
    expect(Array.from(record.subarray(16, 25))).toEqual([1, -1, -1, -1, -1, -1, -1, -1, -1]);
    const back = unpackMaterial(record);
    expect(back.type).toBe('principled');
    // A transmitting principled material is a solid's boundary: never two-sided.
    expect(back.twoSided).toBe(false);
    expect(unpackMaterial(packMaterial(principled({}), true)).twoSided).toBe(true);
  });
});

interface FurnaceCase {
  material: Record<string, unknown>;
  mitsuba: { theta: number; mean: Vec3; standardError: Vec3 }[];
}
const FURNACE: FurnaceCase[] = JSON.parse(readFileSync(new URL('../../../test/fixtures/furnace-principled/cases.json', import.meta.url), 'utf8'));

/**
 * The kernels report channel 0 of a sample's weight. Without a tint the
 * base color enters each channel alone, so the material with channel c's
 * base color in every channel gives channel c; with specTint or sheenTint
 * (baseColor / luminance) the channels mix, and only channel 0 of the
 * material itself is tested.
 */
function channels(m: PrincipledMaterial): [number, Material][] {
  if (m.specTint > 0 || (m.sheen > 0 && m.sheenTint > 0)) return [[0, m]];
  const base = m.baseColor as Vec3;
  return [0, 1, 2].map((c) => [c, { ...m, baseColor: [base[c], base[c], base[c]] }]);
}

const direction = (theta: number): Vec3 => [Math.sin((theta * Math.PI) / 180), 0, Math.cos((theta * Math.PI) / 180)];

const SAMPLER_CASES: { name: string; material: Record<string, unknown>; theta: number; sub?: number }[] = [
  { name: 'default', material: {}, theta: 30 },
  { name: 'metal', material: { baseColor: [1, 0.78, 0.34], metallic: 1, roughness: 0.3 }, theta: 60 },
  { name: 'clear coat', material: { baseColor: [0.05, 0.15, 0.6], roughness: 0.6, clearcoat: 1, clearcoatGloss: 0.3 }, theta: 45 },
  { name: 'sheen, tinted', material: { baseColor: [0.5, 0.2, 0.6], roughness: 0.9, sheen: 1, sheenTint: 0.5, specTint: 0.5 }, theta: 70 },
  { name: 'transmission, outside', material: { roughness: 0.5, specTrans: 1 }, theta: 40, sub: 32 },
  { name: 'transmission, inside', material: { roughness: 0.6, specTrans: 1, ior: 1.33 }, theta: 140, sub: 32 },
  { name: 'everything, outside', material: { metallic: 0.2, specTrans: 0.5, clearcoat: 0.5, clearcoatGloss: 0.2, sheen: 0.5, ior: 1.6 }, theta: 60, sub: 32 },
  { name: 'everything, inside', material: { metallic: 0.2, specTrans: 0.5, clearcoat: 0.5, sheen: 0.5, roughness: 0.7, ior: 1.6 }, theta: 120, sub: 32 },
];

describe('principled on the GPU', () => {
  const session = useRenderSession();

  for (const { name, material, theta, sub } of SAMPLER_CASES) {
    it(`sampler agrees with its pdf (chi-square): ${name}, view ${theta} deg`, async () => {
      const m = principled(material);
      const result = await samplerChiSquare(session(), m, direction(theta), 5, { sub });
      if (m.specTrans === 0) expect(result.belowHorizon).toBe(0);
      else expect(result.belowHorizon, 'transmission').toBeGreaterThan(0);
      expect(result.validFraction, 'most samples must be valid').toBeGreaterThan(0.5);
      // Samples whose microfacet sends them to the wrong side are dropped: the pdf's mass is the valid share.
      expect(Math.abs(result.mass - result.validFraction), JSON.stringify(result)).toBeLessThan(0.01);
      expect(result.chiSquare.degreesOfFreedom).toBeGreaterThan(20);
      expect(result.chiSquare.pValue, JSON.stringify(result)).toBeGreaterThan(1e-4);
    });
  }

  it("sample weights are f / pdf and average to Mitsuba's directional albedo of the exported BSDF", async () => {
    for (const furnace of FURNACE) {
      const m = principled(furnace.material);
      for (const { theta, mean, standardError } of furnace.mitsuba) {
        for (const [c, material] of channels(m)) {
          const ours = await bsdfWeights(session(), material, direction(theta));
          const summary = JSON.stringify({ material: furnace.material, theta, c, ours, mitsuba: mean[c] });
          expect(ours.worstRatioError, summary).toBeLessThan(1e-4);
          // 5 sigma of both estimates (ours: 65k samples, Mitsuba's: 400k).
          expect(Math.abs(ours.mean - mean[c]), summary).toBeLessThan(5 * Math.hypot(ours.standardError, standardError[c]));
        }
      }
    }
  });
});
