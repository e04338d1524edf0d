import { describe, expect, it } from 'vitest';
import { toMitsubaXml } from '../../scene/mitsuba';
import { parseScene } from '../../scene/schema';
import { serializeScene } from '../../scene/serialize';
import { lightArea, lightPower } from '../registry';
import { parseLight, problems, sceneWith } from '../../../test/support/lights';

describe('rectangle light', () => {
  it('fills its defaults and round-trips', () => {
    const l = parseLight({ type: 'rectangle', position: [0, 2, 0], size: [2, 1] });
    expect(l).toEqual({ type: 'rectangle', position: [0, 2, 0], rotation: [0, 0, 0], size: [2, 1], color: [1, 1, 1], intensity: 1 });
    const scene = parseScene(sceneWith([l]));
    expect(parseScene(serializeScene(scene))).toEqual(scene);
  });

  it('emits straight down without rotation: half-axes w/2 along x and h/2 along z, cross(u, v) = -y', () => {
    const shape = lightArea(parseLight({ type: 'rectangle', position: [1, 2, 3], size: [2, 1] }))!;
    expect(shape.u).toEqual([1, 0, 0]);
    expect(shape.v[2]).toBeCloseTo(0.5, 12);
    expect(shape.area).toBe(2);
    const [u, v] = [shape.u, shape.v];
    expect([u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]].map((x) => x / 0.5)).toEqual([0, -1, 0]);
  });

  it('turns its frame as meshes turn: 90 degrees about z makes it emit towards +x', () => {
    const { u, v } = lightArea(parseLight({ type: 'rectangle', position: [0, 0, 0], rotation: [0, 0, 90], size: [2, 2] }))!;
    const n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
    expect(n[0]).toBeCloseTo(1, 12);
    expect(Math.abs(n[1]) + Math.abs(n[2])).toBeLessThan(1e-12);
  });

  it('reports pi * area * luminance as its power (one face emits)', () => {
    expect(lightPower(parseLight({ type: 'rectangle', position: [0, 0, 0], size: [2, 0.5], intensity: 3 }), { radius: 1 })).toBeCloseTo(Math.PI * 3, 10);
  });

  it('names the key of a bad size', () => {
    expect(problems({ type: 'rectangle', position: [0, 0, 0], size: [0, 1] })).toEqual(['lights[0].size[0]: must be > 0']);
    expect(problems({ type: 'rectangle', position: [0, 0, 0], size: [1, -2] })).toEqual(['lights[0].size[1]: must be > 0']);
    expect(problems({ type: 'rectangle', position: [0, 0, 0], size: 1 })).toEqual(['lights[0].size: must be [w, h], each > 0']);
    expect(problems({ type: 'rectangle', position: [0, 0, 0] })).toEqual(['lights[0].size: required']);
    expect(problems({ type: 'rectangle', position: [0, 0, 0], size: [1, 1], radius: 1 })).toEqual(['lights[0].radius: unknown key for this type (see "type", or "map" for environments)']);
  });

  it('exports a rectangle shape with the format transform and a one-sided area emitter', () => {
    const xml = toMitsubaXml(parseScene(sceneWith([{ type: 'rectangle', position: [1, 2, 3], rotation: [10, 20, 30], size: [2, 1], intensity: 4 }])));
    const shape = xml.slice(xml.indexOf('<shape type="rectangle">', xml.indexOf('</sensor>')));
    expect(shape).toMatch(/<scale value="1, 0.5, 1"\/>\s*<rotate x="1" angle="90"\/>\s*<rotate x="1" angle="10"\/>\s*<rotate y="1" angle="20"\/>\s*<rotate z="1" angle="30"\/>\s*<translate value="1, 2, 3"\/>/);
    expect(shape).toMatch(/<emitter type="area">\s*<rgb name="radiance" value="4, 4, 4"\/>/);
  });
});
