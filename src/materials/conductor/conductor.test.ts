/**
 * The conductor, as Mitsuba tests a plugin (test_conductor.py): its schema
 * and export; its sampler against its pdf (chi-square, on the real GLSL);
 * its sample weights against Mitsuba's own directional albedo of the
 * exported BSDF (the furnace values of
 * test/fixtures/furnace-conductor/cases.json, made by
 * scripts/make-conductor-furnace.ts); and the ideal mirror ("none") in the
 * white furnace, exactly 1. conductor.json against its Mitsuba reference is
 * in test/browser/references.test.ts with the other scenes.
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { materialSchema, normalizeMaterial, type Material } from '../registry';
import { toMitsubaXml } from '../../scene/mitsuba';
import { parseScene, safeParseScene } from '../../scene/schema';
import { serializeScene } from '../../scene/serialize';
import type { Scene, Vec3 } from '../../scene/types';
import { useRenderSession, renderLinear } from '../../../test/support/browser';
import { bsdfWeights, expectSamplerMatchesPdf, samplerChiSquare } from '../../../test/support/bsdfKernels';
import { METALS } from './metals';
import type { ConductorMaterial } from './kind';

const camera = { position: [0, 0, 4], target: [0, 0, 0] };
const sceneWith = (material: unknown, version = 3) => ({ version, camera, spheres: [{ center: [0, 0, 0], radius: 1, material }] });
const conductor = (input: Record<string, unknown>) =>
  normalizeMaterial(materialSchema('conductor')!.parse({ type: 'conductor', ...input }) as Record<string, unknown>) as ConductorMaterial;

describe('conductor: schema, serialization, export', () => {
  it('defaults to aluminium, smooth and untinted, with Mitsuba RGB eta and k', () => {
    const m = parseScene(sceneWith({ type: 'conductor' })).spheres[0].material;
    expect(m).toEqual({ type: 'conductor', metal: 'Al', eta: [...METALS.Al.eta], k: [...METALS.Al.k], roughness: 0, color: [1, 1, 1] });
  });

  it('takes eta and k given instead of a metal, and round-trips through the serializer', () => {
    const scene = parseScene(sceneWith({ type: 'conductor', eta: [0.2, 0.9, 1.1], k: [3.9, 2.45, 2.1], roughness: 0.7, color: '#ffeecc' }));
    expect(scene.spheres[0].material).not.toHaveProperty('metal');
    const again = parseScene(serializeScene(scene));
    expect(again).toEqual(scene);
    expect(serializeScene(parseScene(sceneWith({ type: 'conductor', metal: 'Cu' }))).version).toBe(3);
  });

  it.each([
    [{ type: 'conductor', metal: 'Au', eta: [1, 1, 1] }, 'spheres[0].material.eta', 'not allowed with "metal"'],
    [{ type: 'conductor', eta: [1, 1, 1] }, 'spheres[0].material.k', 'required with "eta"'],
    [{ type: 'conductor', k: [1, 1, 1] }, 'spheres[0].material.eta', 'required with "k"'],
    [{ type: 'conductor', metal: 'Unobtainium' }, 'spheres[0].material.metal', 'must be one of'],
    [{ type: 'conductor', metal: 'AlSb' }, 'spheres[0].material.metal', 'must be one of'],
    [{ type: 'conductor', eta: [1, 0, 1], k: [1, 1, 1] }, 'spheres[0].material.eta[1]', 'must be > 0'],
    [{ type: 'conductor', roughness: 2 }, 'spheres[0].material.roughness', 'must be <= 1'],
    [{ type: 'conductor', ior: 1.5 }, 'spheres[0].material.ior', 'unknown key for this type'],
  ])('rejects %j at its key', (material, path, message) => {
    const result = safeParseScene(sceneWith(material));
    expect(result.ok).toBe(false);
    if (!result.ok) expect(result.issues).toContainEqual({ path, message: expect.stringContaining(message) });
  });

  it('needs version 3 and is allowed on the ground', () => {
    const result = safeParseScene(sceneWith({ type: 'conductor' }, 2));
    expect(result.ok).toBe(false);
    if (!result.ok) expect(result.issues).toContainEqual({ path: 'spheres[0].material.type', message: 'requires "version": 3' });
    const ground = parseScene({ version: 3, camera, ground: { material: { type: 'conductor', metal: 'Ag', roughness: 0.2 } } });
    expect(ground.ground?.material.type).toBe('conductor');
  });

  it('exports as conductor / roughconductor with the metal by name or eta and k, two-sided on meshes', () => {
    const scene = parseScene({
      version: 3,
      camera,
      spheres: [
        { center: [0, 0, 0], radius: 1, material: { type: 'conductor', metal: 'Au' } },
        { center: [2, 0, 0], radius: 1, material: { type: 'conductor', eta: [1, 2, 3], k: [4, 5, 6], roughness: 0.5, color: [1, 0.5, 0.25] } },
      ],
      meshes: [{ file: 'a.obj', material: { type: 'conductor', metal: 'Cu', roughness: 0.2 } }],
    });
    const xml = toMitsubaXml(scene, { meshPath: () => 'a.ply' });
    expect(xml).toMatch(/<bsdf type="conductor">\s*<string name="material" value="Au"\/>/);
    expect(xml).toMatch(/<bsdf type="roughconductor">\s*<string name="distribution" value="ggx"\/>\s*<float name="alpha" value="0.25"\/>/);
    expect(xml).toContain('<rgb name="eta" value="1, 2, 3"/>');
    expect(xml).toContain('<rgb name="k" value="4, 5, 6"/>');
    expect(xml).toContain('<rgb name="specular_reflectance" value="1, 0.5, 0.25"/>');
    expect(xml).toMatch(/<bsdf type="twosided">\s*<bsdf type="roughconductor">\s*<string name="distribution" value="ggx"\/>\s*<float name="alpha" value="0.04000000000000001"\/>\s*[^]*?value="Cu"/);
  });
});

interface FurnaceCase {
  material: Record<string, unknown>;
  mitsuba: { theta: number; mean: Vec3; standardError: Vec3 }[];
}
const FURNACE: FurnaceCase[] = JSON.parse(readFileSync(new URL('../../../test/fixtures/furnace-conductor/cases.json', import.meta.url), 'utf8'));

/** The same metal with channel c in every channel (the kernels report channel 0 of a sample's weight). */
function channel(m: ConductorMaterial, c: number): Material {
  const one = (v: Vec3): Vec3 => [v[c], v[c], v[c]];
  return { type: 'conductor', eta: one(m.eta), k: one(m.k), roughness: m.roughness, color: one(m.color) };
}

const direction = (theta: number): Vec3 => [Math.sin((theta * Math.PI) / 180), 0, Math.cos((theta * Math.PI) / 180)];

describe('conductor on the GPU', () => {
  const session = useRenderSession();

  for (const { roughness, theta, metal } of [{ roughness: 0.3, theta: 30, metal: 'Au' }, { roughness: 0.8, theta: 70, metal: 'Cu' }]) {
    it(`rough sampler agrees with its pdf (chi-square): ${metal}, roughness ${roughness}, view ${theta} deg`, async () => {
      const result = await samplerChiSquare(session(), conductor({ metal, roughness }), direction(theta));
      expectSamplerMatchesPdf(result);
    });
  }

  it("sample weights are f / pdf and average to Mitsuba's directional albedo of the exported BSDF", async () => {
    for (const furnace of FURNACE) {
      const m = conductor(furnace.material);
      for (const { theta, mean, standardError } of furnace.mitsuba) {
        // Channel 0 at every angle; all three channels at 45 degrees.
        for (const c of theta === 45 ? [0, 1, 2] : [0]) {
          const ours = await bsdfWeights(session(), channel(m, c), direction(theta));
          const summary = JSON.stringify({ material: furnace.material, theta, c, ours, mitsuba: mean[c] });
          expect(ours.worstRatioError, summary).toBeLessThan(1e-4);
          // 5 sigma of both estimates (ours: 65k samples, Mitsuba's: 400k).
          expect(Math.abs(ours.mean - mean[c]), summary).toBeLessThan(5 * Math.hypot(ours.standardError, standardError[c]));
        }
      }
    }
  });

  it('"none" at roughness 0 is an ideal mirror: exactly 1 in the white furnace', async () => {
    const scene: Scene = parseScene({
      version: 3,
      camera,
      image: { width: 48, height: 48 },
      environment: { color: [1, 1, 1], intensity: 1 },
      spheres: [{ center: [0, 0, 0], radius: 1.2, material: { type: 'conductor', metal: 'none' } }],
    });
    const image = await renderLinear(session(), scene, 4, 5);
    for (let p = 0; p < image.width * image.height; p++) {
      for (let c = 0; c < 3; c++) expect(image.data[p * 4 + c]).toBe(1);
      expect(image.data[p * 4 + 3], 'rejected non-finite samples').toBe(0);
    }
  });
});
