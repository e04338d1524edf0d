import { describe, expect, it } from 'vitest';
import { toMitsubaXml } from '../../scene/mitsuba';
import { parseScene } from '../../scene/schema';
import { lightPower } from '../registry';
import { parseLight, problems, sceneWith } from '../../../test/support/lights';

describe('directional light', () => {
  it('fills its defaults, keeping the direction as given', () => {
    expect(parseLight({ type: 'directional', direction: [0, -2, 0] })).toEqual({ type: 'directional', direction: [0, -2, 0], color: [1, 1, 1], irradiance: 1 });
  });
  it("reports pbrt-v4's power: the irradiance through the scene's bounding disk", () => {
    expect(lightPower(parseLight({ type: 'directional', direction: [0, -1, 0], irradiance: 2 }), { radius: 3 })).toBeCloseTo(Math.PI * 9 * 2, 10);
  });
  it('names a zero direction', () => {
    expect(problems({ type: 'directional', direction: [0, 0, 0] })).toEqual(['lights[0].direction: must not be zero length']);
    expect(problems({ type: 'directional', direction: [0, -1, 0], intensity: 1 })[0]).toMatch(/^lights\[0\]\.intensity: unknown key/);
  });
  it('exports a directional emitter with the unit direction', () => {
    const xml = toMitsubaXml(parseScene(sceneWith([{ type: 'directional', direction: [0, -2, 0], irradiance: 3 }])));
    expect(xml).toMatch(/<emitter type="directional">\s*<vector name="direction" value="0, -1, 0"\/>\s*<rgb name="irradiance" value="3, 3, 3"\/>/);
  });
});
