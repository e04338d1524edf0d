import { describe, expect, it } from 'vitest';
import { parseScene } from '../../scene/schema';
import { serializeScene } from '../../scene/serialize';
import { lightPower } from '../registry';
import { parseLight, problems, sceneWith } from '../../../test/support/lights';

describe('sphere light (the default kind)', () => {
  it('is what a light without `type` is, in every version; version 1 and 2 documents are written without `type`', () => {
    const json = { position: [0, 3, 0], radius: 0.5, intensity: 2 };
    for (const version of [1, 2, 3]) expect(parseLight(json, version)).toEqual({ type: 'sphere', position: [0, 3, 0], radius: 0.5, color: [1, 1, 1], intensity: 2 });
    expect(serializeScene(parseScene(sceneWith([json], 1))).lights).toEqual([{ position: [0, 3, 0], radius: 0.5, color: [1, 1, 1], intensity: 2 }]);
    expect(serializeScene(parseScene(sceneWith([{ type: 'rectangle', position: [0, 1, 0], size: [1, 1] }, json]))).lights![1]).toMatchObject({ type: 'sphere' });
  });
  it('reports pi * 4 pi r^2 * luminance as its power', () => {
    expect(lightPower(parseLight({ position: [0, 3, 0], radius: 0.5, intensity: 2 }), { radius: 1 })).toBeCloseTo(2 * Math.PI * Math.PI, 10);
  });
  it('needs version 3 for a `type` key, and names unknown types', () => {
    expect(problems({ type: 'sphere', position: [0, 3, 0], radius: 1 }, 2)).toEqual(['lights[0].type: requires "version": 3']);
    expect(problems({ type: 'rectangle', position: [0, 3, 0], size: [1, 1] }, 1)).toEqual(['lights[0].type: requires "version": 3']);
    expect(problems({ type: 'area', position: [0, 3, 0] })).toEqual(['lights[0].type: must be "sphere" or "rectangle" or "disk" or "point" or "spot" or "directional"']);
  });
});
