import { describe, expect, it } from 'vitest';
import { toMitsubaXml } from '../../scene/mitsuba';
import { parseScene } from '../../scene/schema';
import { lightPower } from '../registry';
import { parseLight, problems, sceneWith } from '../../../test/support/lights';

describe('point light', () => {
  it('fills its defaults', () => {
    expect(parseLight({ type: 'point', position: [0, 2, 0] })).toEqual({ type: 'point', position: [0, 2, 0], color: [1, 1, 1], intensity: 1 });
  });
  it('reports 4 pi I as its power', () => {
    expect(lightPower(parseLight({ type: 'point', position: [0, 2, 0], intensity: 2 }), { radius: 1 })).toBeCloseTo(8 * Math.PI, 10);
  });
  it('names bad keys', () => {
    expect(problems({ type: 'point', position: [0, 2, 0], intensity: -1 })).toEqual(['lights[0].intensity: must be >= 0']);
    expect(problems({ type: 'point' })).toEqual(['lights[0].position: required']);
  });
  it('exports a point emitter of that intensity', () => {
    const xml = toMitsubaXml(parseScene(sceneWith([{ type: 'point', position: [1, 2, 3], color: [1, 0.5, 0.25], intensity: 4 }])));
    expect(xml).toMatch(/<emitter type="point">\s*<point name="position" value="1, 2, 3"\/>\s*<rgb name="intensity" value="4, 2, 1"\/>/);
  });
});
