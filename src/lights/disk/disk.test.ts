import { describe, expect, it } from 'vitest';
import { toMitsubaXml } from '../../scene/mitsuba';
import { parseScene } from '../../scene/schema';
import { lightArea, lightPower } from '../registry';
import { parseLight, problems, sceneWith } from '../../../test/support/lights';

describe('disk light', () => {
  it('fills its defaults', () => {
    expect(parseLight({ type: 'disk', position: [0, 2, 0], radius: 0.5 })).toEqual({ type: 'disk', position: [0, 2, 0], rotation: [0, 0, 0], radius: 0.5, color: [1, 1, 1], intensity: 1 });
  });

  it('has half-axes of its radius and area pi r^2, and power pi * area * luminance', () => {
    const l = parseLight({ type: 'disk', position: [0, 2, 0], radius: 0.5, intensity: 2 });
    const shape = lightArea(l)!;
    expect(shape.u).toEqual([0.5, 0, 0]);
    expect(shape.area).toBeCloseTo(Math.PI / 4, 12);
    expect(lightPower(l, { radius: 1 })).toBeCloseTo((Math.PI * Math.PI) / 2, 10);
  });

  it('names the key of a radius of 0', () => {
    expect(problems({ type: 'disk', position: [0, 0, 0], radius: 0 })).toEqual(['lights[0].radius: must be > 0']);
  });

  it('exports a disk shape scaled by its radius', () => {
    const xml = toMitsubaXml(parseScene(sceneWith([{ type: 'disk', position: [0, 2, 0], radius: 0.25, color: [1, 0.5, 0.25], intensity: 4 }])));
    expect(xml).toMatch(/<shape type="disk">\s*<transform name="to_world">\s*<scale value="0.25, 0.25, 1"\/>\s*<rotate x="1" angle="90"\/>/);
    expect(xml).toMatch(/<rgb name="radiance" value="4, 2, 1"\/>/);
  });
});
