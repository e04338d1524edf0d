import { describe, expect, it } from 'vitest';
import { buildAliasTable } from '../../src/render/aliasTable';
import { selectCausticGuides } from '../../src/render/causticGuides';
import { defineRecord, packRecord, recordGlsl } from '../../src/render/layout/records';
import {
  BLOCK_VEC4S, DATA_TEXELS, EMITTER, EMITTER_KINDS, GUIDE_FIELDS, HEADER, MATERIAL, MAX_GUIDES, MAX_SCENE_SPHERES, MESH, SECTIONS, SPHERE,
} from '../../src/render/layout/scene';
import { BASE_FEATURES, emitterChoiceWeights, type PackedScene } from '../../src/render/packScene';
import { materialGlsl, unpackMaterial } from '../../src/materials/registry';
import { packScene } from '../../src/render/packScene';
import { parseScene } from '../../src/scene/schema';
import { DATA_ROWS, SCENE_ROW_TEXELS, TABLE_TEXELS, sceneLayoutDefines } from '../../src/render/layout/scene';
import { MAX_SPHERES } from '../../src/scene/limits';
import { readRecord } from '../support/records';
import { choiceEntry } from '../support/lightChoice';

const camera = { position: [0, 1, 5], target: [0, 0, 0] };

const globalChoice = (packed: PackedScene, i: number) => choiceEntry(packed, i);

/** Reads record `index` of a table back into named fields, through the layout's own field table. */
/** A sphere's center.xyz and radius from the sphere-geometry table. */
const sphereGeometry = (data: Float32Array, i: number) => Array.from(data.subarray((SECTIONS.sphereGeometry + i) * 4, (SECTIONS.sphereGeometry + i) * 4 + 4));


/** Material record `index` of the table, read back through its kind's layout. */
function readMaterial(data: Float32Array, index: number) {
  const base = (SECTIONS.materials + index * MATERIAL.texels) * 4;
  return unpackMaterial(data.subarray(base, base + MATERIAL.texels * 4));
}

describe('record layouts', () => {
  it('lay fields out in order without a vec3 straddling two texels', () => {
    const layout = defineRecord('Test', [['a', 'float'], ['b', 'float'], ['v', 'vec3'], ['i', 'int']]);
    expect(layout.fields.map((f) => [f.texel, f.offset])).toEqual([[0, 0], [0, 1], [1, 0], [1, 3]]);
    expect(layout.texels).toBe(2);
    expect(Array.from(packRecord(layout, { a: 1, v: [2, 3, 4], i: 5 }))).toEqual([1, 0, 0, 0, 2, 3, 4, 5]);
    expect(() => packRecord(layout, { nope: 1 })).toThrow(/no field/);
    expect(() => packRecord(layout, { v: [1, 2] })).toThrow(/expected 3/);
  });

  it('generate GLSL readers that take each field from the texel and component the packer wrote', () => {
    const glsl = recordGlsl(SPHERE, 'fetch');
    for (const f of SPHERE.fields) {
      const swizzle = 'xyzw'.slice(f.offset, f.offset + (f.type === 'vec3' ? 3 : 1));
      expect(glsl).toContain(`r.${f.name} = ${f.type === 'int' ? `int(t${f.texel}.${swizzle})` : `t${f.texel}.${swizzle}`};`);
    }
    expect(glsl).toContain(`vec4 t${SPHERE.texels - 1} = fetch(first + ${SPHERE.texels - 1});`);
  });

  it('generate the material reader for every texel of the record', () => {
    const glsl = materialGlsl();
    for (let t = 0; t < MATERIAL.texels; t++) expect(glsl).toContain(`m.t${t} = sceneData(first + ${t});`);
    expect(glsl).toMatch(/struct DielectricParams \{\n  vec3 color;\n  float roughness;\n  float ior;\n\};/);
    expect(glsl).toContain('p.ior = b.t2.x;');
  });
});

describe('packScene', () => {
  const scene = parseScene({
    version: 2,
    camera,
    environment: { color: [0.5, 0.25, 1], intensity: 2 },
    ground: { height: -1, material: { color: [0.1, 0.2, 0.3], roughness: 0.4 } },
    lights: [{ position: [1, 2, 3], radius: 0.5, color: [1, 0.5, 0.25], intensity: 4 }],
    spheres: [
      { center: [0, 0, 0], radius: 1, material: { color: [0.25, 0.5, 0.75], roughness: 0.5, emission: { color: [1, 1, 1], intensity: 3 } } },
      { center: [3, 0, 0], radius: 2, material: { type: 'dielectric', ior: 1.33, roughness: 0.1, color: [0.9, 1, 1] } },
    ],
  });
  const packed = packScene(scene);

  it('writes spheres, then lights as emitter-only spheres, each with its own material', () => {
    expect(packed.data.length).toBe(DATA_TEXELS * 4);
    expect(packed.block.length).toBe(BLOCK_VEC4S * 4);
    const spheres = [0, 1, 2].map((i) => readRecord(packed.data, SECTIONS.spheres, SPHERE, i));
    expect([0, 1, 2].map((i) => { const g = sphereGeometry(packed.data, i); return [g.slice(0, 3), g[3]]; })).toEqual([[[0, 0, 0], 1], [[3, 0, 0], 2], [[1, 2, 3], 0.5]]);
    const materials = spheres.map((s) => readMaterial(packed.data, s.material as number));
    expect(materials[0]).toMatchObject({ type: 'standard', twoSided: false, color: [0.25, 0.5, 0.75], roughness: 0.5, emission: [3, 3, 3] });
    expect(materials[1].type).toBe('dielectric');
    expect(materials[1].ior).toBeCloseTo(1.33, 6);
    expect(materials[1].roughness).toBeCloseTo(0.1, 6);
    expect(materials[2]).toMatchObject({ type: 'emitterOnly', emission: [4, 2, 1] });
  });

  it('lists emitters by power with probabilities that match the spheres they point at', () => {
    const header = readRecord(packed.block, 0, HEADER, 0);
    expect(header).toMatchObject({ sphereCount: 3, emitterCount: 2, groundEnabled: 1, groundHeight: -1, environment: [1, 0.5, 2] });
    const emitters = [0, 1].map((i) => readRecord(packed.data, SECTIONS.emitters, EMITTER, i));
    expect(emitters.map((e) => e.primitive)).toEqual([0, 2]);
    // Power ~ luminance * r^2: 3 * 1 vs luminance([4, 2, 1]) * 0.25.
    const light = (0.2126 * 4 + 0.7152 * 2 + 0.0722 * 1) * 0.25;
    expect(globalChoice(packed, 0).pdf).toBeCloseTo(3 / (3 + light), 6);
    expect(globalChoice(packed, 1).pdf).toBeCloseTo(light / (3 + light), 6);
    emitters.forEach((e, i) => expect(readRecord(packed.data, SECTIONS.spheres, SPHERE, e.primitive as number).emitter).toBe(i));
    expect(readRecord(packed.data, SECTIONS.spheres, SPHERE, 1).emitter).toBe(-1);
    const ground = readMaterial(packed.data, header.groundMaterial as number);
    expect(ground).toMatchObject({ type: 'standard', roughness: expect.closeTo(0.4, 6) });
    expect(globalChoice(packed, 1).alias).toBe(0);
    expect(packed.features).toEqual({ ...BASE_FEATURES, materials: ['dielectric'] });
  });

  it('makes an environment map an emitter picked by its power, and glass on meshes a glass feature', () => {
    const withMap = parseScene({
      version: 2,
      camera,
      environment: { map: 'sky.hdr', intensity: 2 },
      lights: [{ position: [0, 3, 0], radius: 0.5, intensity: 10 }],
      meshes: [{ file: 'gem.obj', material: { type: 'dielectric' } }],
    });
    const integral = 4 * Math.PI; // a white map of radiance 1
    const packed = packScene(withMap, { environmentIntegral: integral });
    const header = readRecord(packed.block, 0, HEADER, 0);
    expect(header.emitterCount).toBe(2);
    const environment = readRecord(packed.data, SECTIONS.emitters, EMITTER, 1);
    expect(environment.kind).toBe(EMITTER_KINDS.environment);
    expect(header.environmentEmitter).toBe(1);
    // pi R^2 * integral * intensity against pi * 4 pi r^2 * luminance; R = 1.5 (camera to light centre spread), at least 1.
    const light = 4 * Math.PI * Math.PI * 0.25 * 10;
    const points = [[0, 1, 5], [0, 3, 0], [0, 0, 0]];
    const c = [0, 1, 2].map((k) => points.reduce((sum, p) => sum + p[k], 0) / 3);
    let radius = 1;
    for (const p of points) radius = Math.max(radius, Math.hypot(p[0] - c[0], p[1] - c[1], p[2] - c[2]));
    radius = Math.max(radius, Math.hypot(0 - c[0], 3 - c[1], 0 - c[2]) + 0.5);
    const sky = Math.PI * radius * radius * integral * 2;
    expect(globalChoice(packed, 1).pdf).toBeCloseTo(sky / (sky + light), 6);
    expect(packed.features).toEqual({ ...BASE_FEATURES, materials: ['dielectric'], environmentMap: true, meshes: true });
    // Glass on a mesh stays one-sided in the record: a solid's boundary has both sides already.
    expect(readMaterial(packed.data, packed.meshMaterials[0])).toMatchObject({ type: 'dielectric', twoSided: false });
    // Without the map's distribution (or with a black map) the environment is no emitter.
    expect(readRecord(packScene(withMap).block, 0, HEADER, 0)).toMatchObject({ emitterCount: 1, environmentEmitter: -1 });
  });

  it("writes each mesh record's first material slot (materialBase) and light-sampling density", () => {
    const scene = (ground: boolean, spheres: number) =>
      parseScene({
        version: 2,
        camera,
        ...(ground ? { ground: { height: 0, material: { color: [0.5, 0.5, 0.5], roughness: 1 } } } : {}),
        spheres: Array.from({ length: spheres }, (_, i) => ({ center: [i, 0, 0], radius: 0.5, material: { color: [0.5, 0.5, 0.5], roughness: 1 } })),
        lights: [{ position: [0, 3, 0], radius: 0.5, intensity: 10 }],
        meshes: [
          { file: 'a.obj', material: { type: 'dielectric' } },
          { file: 'b.obj', material: { color: [1, 1, 1], roughness: 1, emission: { color: [1, 1, 1], intensity: 2 } } },
        ],
      });
    const sizes = [{ area: 2, triangles: 10 }, { area: 4, triangles: 20 }];
    for (const [ground, spheres] of [[true, 1], [false, 1], [true, 3]] as const) {
      const packed = packScene(scene(ground, spheres), { meshes: sizes });
      const records = [0, 1].map((i) => readRecord(packed.data, SECTIONS.meshes, MESH, i));
      // Spheres, lights, then the ground, then the meshes: the slots shift, the records follow.
      expect(packed.meshMaterials).toEqual([spheres + 1 + (ground ? 1 : 0), spheres + 2 + (ground ? 1 : 0)]);
      expect(records.map((r) => r.materialBase)).toEqual(packed.meshMaterials);
      expect(readMaterial(packed.data, records[0].materialBase as number).type).toBe('dielectric');
      const emitter = readRecord(packed.data, SECTIONS.emitters, EMITTER, 1);
      expect(emitter).toMatchObject({ kind: EMITTER_KINDS.mesh, primitive: 1 });
      expect(records[1]).toMatchObject({ emitter: 1, inverseArea: 0.25 });
      expect(records[0].emitter).toBe(-1);
    }
  });

  it('packs an empty scene with zero counts and a black environment', () => {
    const empty = packScene(parseScene({ camera }));
    expect(readRecord(empty.block, 0, HEADER, 0)).toMatchObject({ sphereCount: 0, emitterCount: 0, groundEnabled: 0, environment: [0, 0, 0] });
    expect(empty.features).toEqual(BASE_FEATURES);
  });

  it('makes opaque materials on meshes two-sided and compiles in only the kinds used', () => {
    const metals = parseScene({
      version: 3,
      camera,
      ground: { material: { type: 'conductor', metal: 'Au' } },
      meshes: [{ file: 'a.obj', material: { roughness: 0.5 } }, { file: 'b.obj', material: { type: 'conductor', eta: [1, 2, 3], k: [4, 5, 6] } }],
    });
    const packed = packScene(metals);
    expect(packed.features.materials).toEqual(['conductor']);
    expect(readMaterial(packed.data, packed.meshMaterials[0])).toMatchObject({ type: 'standard', twoSided: true });
    const metal = readMaterial(packed.data, packed.meshMaterials[1]);
    expect(metal).toMatchObject({ type: 'conductor', twoSided: true, eta: [1, 2, 3], k: [4, 5, 6], color: [1, 1, 1], roughness: 0 });
    const ground = readMaterial(packed.data, readRecord(packed.block, 0, HEADER, 0).groundMaterial as number);
    expect(ground).toMatchObject({ type: 'conductor', twoSided: false });
    expect((ground.eta as number[])[0]).toBeCloseTo(0.143036, 5);
  });
});

describe('buildAliasTable', () => {
  it('draws every index with its probability (exactly, integrating over u)', () => {
    for (const weights of [[1], [1, 1, 1], [1, 2, 3, 4], [0.001, 5, 0, 2], [10, 1e-6]]) {
      const table = buildAliasTable(weights);
      const n = weights.length;
      const drawn = new Array<number>(n).fill(0);
      // Each slot i covers u in [i/n, (i+1)/n): a fraction `threshold` keeps i, the rest goes to the alias.
      table.threshold.forEach((t, i) => {
        drawn[i] += t / n;
        drawn[table.alias[i]] += (1 - t) / n;
      });
      const total = weights.reduce((a, b) => a + b, 0);
      weights.forEach((w, i) => {
        expect(drawn[i]).toBeCloseTo(w / total, 9);
        expect(table.pdf[i]).toBeCloseTo(w / total, 12);
      });
    }
  });

  it('keeps every index (the plain uniform choice) for equal weights', () => {
    expect(buildAliasTable([2, 2, 2]).threshold).toEqual([1, 1, 1]);
  });
});

describe('emitterChoiceWeights', () => {
  it('is the powers without a delta light, half power share and half uniform with one', () => {
    expect(emitterChoiceWeights([1, 3], false)).toEqual([1, 3]);
    const mixed = emitterChoiceWeights([1, 3], true);
    expect(mixed[0]).toBeCloseTo(0.5 * 0.25 + 0.25, 12);
    expect(mixed[1]).toBeCloseTo(0.5 * 0.75 + 0.25, 12);
    // No probability falls below half the uniform one, however weak the light.
    const weak = emitterChoiceWeights([1e-9, 1, 1, 1], true);
    expect(weak[0] / weak.reduce((a, b) => a + b, 0)).toBeGreaterThanOrEqual(0.5 / 4);
  });

  it('keeps a version-2 scene of sphere lights on the choice by power', () => {
    const scene = parseScene({ camera, lights: [{ position: [0, 4, 0], radius: 0.5, intensity: 10 }, { position: [2, 4, 0], radius: 0.5, intensity: 30 }] });
    const packed = packScene(scene);
    const pdfs = [0, 1].map((i) => globalChoice(packed, readRecord(packed.data, SECTIONS.spheres, SPHERE, i).emitter as number).pdf);
    expect(pdfs[1] / pdfs[0]).toBeCloseTo(3, 5);
  });
});

describe('selectCausticGuides', () => {
  const mirror = (x: number, radius = 1, roughness = 0) => ({ center: [x, 1, 0], radius, material: { color: [0.9, 0.9, 0.9], roughness } });
  const light = (intensity: number, radius = 0.5) => ({ position: [0, 5, 0], radius, intensity });
  const spheresOf = (json: object) => {
    const s = parseScene({ camera, ...json });
    return [
      ...s.spheres.map((x) => ({ center: x.center, radius: x.radius, material: x.material, radiance: x.material.emission ? [1, 1, 1] as [number, number, number] : [0, 0, 0] as [number, number, number] })),
      ...s.lights.map((l) => l.type === 'sphere' ? { center: l.position, radius: l.radius, material: 'emitterOnly' as const, radiance: l.color.map((c) => c * l.intensity) as [number, number, number] } : null!),
    ];
  };

  it('pairs ideal mirrors (alpha below the smooth limit) with emitters, brightest first, at most MAX_GUIDES', () => {
    const json = { lights: [light(10), light(40), light(0)], spheres: [mirror(0, 1, 0.5), mirror(2, 0.5, 0.02), mirror(-2, 1, 0), mirror(4, 1, 0.04)] };
    // Sphere 0 is rough, sphere 3 has alpha = 0.0016 (a glossy lobe, not a mirror), light 2 is dark.
    // Lights follow the 4 spheres: light 1 is sphere 5.
    expect(selectCausticGuides(spheresOf(json))).toEqual([[2, 5], [1, 5]].slice(0, MAX_GUIDES));
    const packed = packScene(parseScene({ camera, ...json }));
    expect(packed.features.guides).toBe(Math.min(MAX_GUIDES, 4));
    const guide = (field: number) => Array.from(packed.block.subarray((HEADER.texels + field) * 4, (HEADER.texels + field) * 4 + 4));
    expect(guide(GUIDE_FIELDS.MIRROR)).toEqual([-2, 1, 0, 1]);
    expect(guide(GUIDE_FIELDS.LIGHT)).toEqual([0, 5, 0, 0.5]);
  });

  it('has no guides without mirrors or without emitters, and never aims glass', () => {
    expect(selectCausticGuides(spheresOf({ lights: [light(10)], spheres: [mirror(0, 1, 1)] }))).toEqual([]);
    expect(selectCausticGuides(spheresOf({ spheres: [mirror(0)] }))).toEqual([]);
    const glass = { center: [0, 1, 0], radius: 1, material: { type: 'dielectric' } };
    expect(selectCausticGuides(spheresOf({ version: 2, lights: [light(10)], spheres: [glass] }))).toEqual([]);
  });
});

describe('the data texture in rows', () => {
  it('is DATA_ROWS whole rows of 2048 texels, the last row the one the tables end in', () => {
    expect(SCENE_ROW_TEXELS).toBe(2048);
    expect(DATA_TEXELS).toBe(DATA_ROWS * SCENE_ROW_TEXELS);
    expect(TABLE_TEXELS).toBeLessThanOrEqual(DATA_TEXELS);
    expect(TABLE_TEXELS).toBeGreaterThan(DATA_TEXELS - SCENE_ROW_TEXELS);
    expect(DATA_ROWS).toBeGreaterThan(1);
    const defines = sceneLayoutDefines();
    expect(defines.SCENE_ROW_TEXELS).toBe(SCENE_ROW_TEXELS);
    expect(1 << defines.SCENE_ROW_BITS).toBe(SCENE_ROW_TEXELS);
  });

  it('packs a record beyond texel 2048 where SECTIONS says, with its own material beyond texel 2048 too', () => {
    // Enough spheres that the material table alone runs into the second row.
    const count = Math.ceil(SCENE_ROW_TEXELS / MATERIAL.texels) + 8;
    expect(count).toBeLessThanOrEqual(MAX_SPHERES);
    const color = (i: number) => [(i % 7) / 7, (i % 11) / 11, (i % 13) / 13];
    const spheres = Array.from({ length: count }, (_, i) => ({ center: [i, -i, 2 * i], radius: 1 + i / 1000, material: { color: color(i), roughness: 1 } }));
    const packed = packScene(parseScene({ camera, spheres }));
    expect(packed.data.length % (SCENE_ROW_TEXELS * 4)).toBe(0);
    expect(packed.data.length).toBe(DATA_TEXELS * 4);
    const last = count - 1;
    const sphereTexel = SECTIONS.spheres + last * SPHERE.texels;
    expect(sphereTexel).toBeGreaterThanOrEqual(SCENE_ROW_TEXELS);
    const sphere = readRecord(packed.data, SECTIONS.spheres, SPHERE, last);
    const geometry = sphereGeometry(packed.data, last);
    expect(geometry.slice(0, 3)).toEqual([last, -last, 2 * last]);
    expect(geometry[3]).toBeCloseTo(1 + last / 1000, 6);
    // The geometry table lies in row 0 (the shader fetches it with row 0).
    expect(SECTIONS.sphereGeometry + MAX_SCENE_SPHERES).toBeLessThanOrEqual(SCENE_ROW_TEXELS);
    const materialTexel = SECTIONS.materials + (sphere.material as number) * MATERIAL.texels;
    expect(materialTexel).toBeGreaterThanOrEqual(SCENE_ROW_TEXELS);
    const material = readMaterial(packed.data, sphere.material as number);
    (material.color as number[]).forEach((c, k) => expect(c).toBeCloseTo(color(last)[k], 6));
    // The shader's address of a texel, (texel & 2047, texel >> 11), names the same float.
    const at = (texel: number) => ((texel >> 11) * SCENE_ROW_TEXELS + (texel & (SCENE_ROW_TEXELS - 1))) * 4;
    expect(packed.data[at(sphereTexel)]).toBe(sphere.material);
    // Past the tables the rectangle is padding, zero.
    expect(packed.data.subarray(TABLE_TEXELS * 4).every((v) => v === 0)).toBe(true);
  });
});
