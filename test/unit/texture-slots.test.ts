/**
 * The page's texture slots as data and pure edits: which controls may be
 * textures (the kinds' `texturable` flags and `texture` controls, checked
 * against the inputs the kinds accept textures on), making an input a
 * texture and a constant again (every result a valid scene), naming a
 * second image of the same file name, and the textured and principled
 * examples (the fixtures, with their files bundled byte for byte).
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { materialLayoutKey, withoutTexture, withTexture } from '../../src/app/materialControls';
import { imageNameFor } from '../../src/app/textureImages';
import { MAP_EXAMPLES, TEXTURE_EXAMPLES } from '../../src/app/examples';
import { bundledMapFile } from '../../src/app/bundledMaps';
import { controlTextureInput, KINDS } from '../../src/materials/registry';
import { parseScene } from '../../src/scene/schema';
import { serializeScene } from '../../src/scene/serialize';
import type { TextureImage } from '../../src/scene/texture/image';
import type { Material } from '../../src/scene/types';

const fixtureJson = (name: string) => JSON.parse(readFileSync(new URL(`../fixtures/scenes/${name}.json`, import.meta.url), 'utf8'));

/** A one-mesh scene with `material`, parsed (throws, naming the key, if the material is invalid there). */
function meshWith(material: Material) {
  const scene = parseScene({ version: 3, camera: { position: [0, 1, 5], target: [0, 1, 0] }, meshes: [{ file: 'box.obj' }] });
  scene.meshes[0].material = material;
  return parseScene(serializeScene(scene));
}

const principled = (): Material => parseScene({ version: 3, camera: { position: [0, 1, 5], target: [0, 1, 0] }, meshes: [{ file: 'b.obj', material: { type: 'principled', baseColor: [0.2, 0.4, 0.6], roughness: 0.3 } }] }).meshes[0].material!;

describe('texturable controls', () => {
  it('are exactly the inputs each kind takes textures on, with the input they feed', () => {
    for (const kind of KINDS) {
      const fromControls = kind.controls.flatMap((c) => (controlTextureInput(c) ? [`${c.key}:${controlTextureInput(c)}`] : [])).sort();
      const accepted = [
        ...(kind.textures ?? []).map((t) => `${t.key}:${t.input}`),
        ...(kind.opacity ? ['opacity:scalar'] : []),
        ...(kind.normalMap ? ['normalMap:normal'] : []),
      ].sort();
      expect(fromControls, kind.type).toEqual(accepted);
    }
  });
});

describe('withTexture and withoutTexture', () => {
  it('make a constant the image as it is, and bring the constant back', () => {
    const m = principled();
    const before = materialLayoutKey(m);
    withTexture(m, 'baseColor', 'wood.png');
    withTexture(m, 'roughness', 'rough.png');
    withTexture(m, 'normalMap', 'bumps.png');
    expect(materialLayoutKey(m)).not.toBe(before);
    const parsed = meshWith(m).meshes[0].material as unknown as Record<string, unknown>;
    expect(parsed.baseColor).toEqual({ image: 'wood.png', channel: 'r', scale: 1, uv: { offset: [0, 0], scale: [1, 1], rotation: 0 } });
    expect(parsed).toEqual(m);
    withoutTexture(m, 'baseColor', [0.2, 0.4, 0.6]);
    withoutTexture(m, 'roughness'); // nothing set aside: the kind's default
    withoutTexture(m, 'normalMap');
    expect(m).toEqual({ ...principled(), roughness: 0.5 });
    expect(materialLayoutKey(m)).toBe(before);
    expect(meshWith(m).meshes[0].material).toEqual(m);
  });

  it('replaces only the image of a texture (channel, scale and uv stay); a texture set aside is no constant', () => {
    const m = principled() as unknown as Record<string, unknown>;
    m.roughness = { image: 'rough.png', channel: 'g', scale: 0.8, uv: { offset: [0.5, 0], scale: [2, 2], rotation: 10 } };
    withTexture(m as unknown as Material, 'roughness', 'other.png');
    expect(m.roughness).toEqual({ image: 'other.png', channel: 'g', scale: 0.8, uv: { offset: [0.5, 0], scale: [2, 2], rotation: 10 } });
    withoutTexture(m as unknown as Material, 'roughness', m.roughness);
    expect(m.roughness).toBe(0.5);
  });
});

describe('imageNameFor', () => {
  const image = (value: number): TextureImage => ({ width: 1, height: 1, format: 'png', encoding: 'u8', data: new Uint8Array([value, 0, 0, 255]) });
  it('keeps the name for a new or the same image; numbers a different one', () => {
    const loaded = new Map([['a.png', image(1)], ['a-2.png', image(2)]]);
    expect(imageNameFor(loaded, 'b.png', image(1))).toBe('b.png');
    expect(imageNameFor(loaded, 'a.png', image(1))).toBe('a.png');
    expect(imageNameFor(loaded, 'a.png', image(2))).toBe('a-2.png');
    expect(imageNameFor(loaded, 'a.png', image(3))).toBe('a-3.png');
    expect(imageNameFor(new Map([['noext', image(1)]]), 'noext', image(2))).toBe('noext-2');
  });
});

describe('the texture examples', () => {
  it('textured is test/fixtures/scenes/textured.json with its files named without folders and the bundled studio map', () => {
    const fixture = fixtureJson('textured');
    const renamed = JSON.parse(JSON.stringify(fixture), (key, value) => ((key === 'image' || key === 'file') && typeof value === 'string' ? value.split('/').pop() : value));
    renamed.environment.map = bundledMapFile('studio');
    expect(serializeScene(parseScene(TEXTURE_EXAMPLES.textured.scene))).toEqual(serializeScene(parseScene(renamed)));
  });

  it('principled is test/fixtures/scenes/principled.json with the bundled sunset map', () => {
    const fixture = fixtureJson('principled');
    fixture.environment.map = bundledMapFile('sunset');
    expect(serializeScene(parseScene(MAP_EXAMPLES.principled))).toEqual(serializeScene(parseScene(fixture)));
  });

  it('bundles the fixtures byte for byte', () => {
    for (const file of ['textures/checker.png', 'textures/grid.png', 'textures/rough.png', 'textures/bumps.png', 'meshes/uvbox.obj']) {
      const bundled = readFileSync(new URL(`../../src/app/exampleFiles/${file.split('/')[1]}`, import.meta.url));
      expect(bundled.equals(readFileSync(new URL(`../fixtures/${file}`, import.meta.url))), file).toBe(true);
    }
  });
});
