import { describe, expect, it } from 'vitest';
import { toMitsubaXml } from '../../scene/mitsuba';
import { parseScene } from '../../scene/schema';
import { serializeScene } from '../../scene/serialize';
import { lightPower } from '../registry';
import { parseLight, problems, sceneWith } from '../../../test/support/lights';
import { spotCone, type SpotLight } from './kind';

const spot = { type: 'spot', position: [0, 3, 0], target: [0, 0, 0] };

describe('spot light', () => {
  it('defaults to a 20 degree cutoff and a beam of 0.75 of it, written out explicitly', () => {
    const l = parseLight({ ...spot, cutoffAngle: 40 }) as SpotLight;
    expect(l).toEqual({ type: 'spot', position: [0, 3, 0], target: [0, 0, 0], color: [1, 1, 1], intensity: 1, cutoffAngle: 40, beamWidth: 30 });
    expect((parseLight(spot) as SpotLight).beamWidth).toBe(15);
    const scene = parseScene(sceneWith([l]));
    expect(serializeScene(scene).lights![0]).toMatchObject({ type: 'spot', beamWidth: 30 });
    expect(parseScene(serializeScene(scene))).toEqual(scene);
  });

  it("packs Mitsuba's falloff constants (a beam as wide as the cutoff has no transition)", () => {
    const cone = spotCone(parseLight({ ...spot, cutoffAngle: 30, beamWidth: 10 }) as SpotLight);
    expect(cone.cosCutoff).toBeCloseTo(Math.cos(Math.PI / 6), 12);
    expect(cone.invTransition).toBeCloseTo(1 / ((20 * Math.PI) / 180), 10);
    expect(spotCone(parseLight({ ...spot, cutoffAngle: 30, beamWidth: 30 }) as SpotLight).invTransition).toBe(0);
  });

  it("reports pbrt-v4's power: 2 pi I (1 - (cos beam + cos cutoff) / 2)", () => {
    const l = parseLight({ ...spot, cutoffAngle: 60, beamWidth: 0, intensity: 2 });
    expect(lightPower(l, { radius: 1 })).toBeCloseTo(2 * Math.PI * 2 * (1 - (1 + 0.5) / 2), 10);
  });

  it('names the key of each bad angle and of a target at the position', () => {
    expect(problems({ ...spot, target: [0, 3, 0] })).toEqual(['lights[0].target: must differ from position']);
    expect(problems({ ...spot, cutoffAngle: 20, beamWidth: 25 })).toEqual(['lights[0].beamWidth: must be <= cutoffAngle (20)']);
    expect(problems({ ...spot, cutoffAngle: 0 })).toEqual(['lights[0].cutoffAngle: must be in (0, 90]']);
    expect(problems({ ...spot, cutoffAngle: 95 })).toEqual(['lights[0].cutoffAngle: must be in (0, 90]']);
    expect(problems({ ...spot, beamWidth: -1 })).toEqual(['lights[0].beamWidth: must be >= 0']);
  });

  it('exports a spot emitter looking at its target', () => {
    const xml = toMitsubaXml(parseScene(sceneWith([{ ...spot, intensity: 5, cutoffAngle: 30, beamWidth: 12 }])));
    expect(xml).toMatch(/<emitter type="spot">\s*<transform name="to_world">\s*<lookat origin="0, 3, 0" target="0, 0, 0" up="1, 0, 0"\/>/);
    expect(xml).toMatch(/<float name="cutoff_angle" value="30"\/>\s*<float name="beam_width" value="12"\/>/);
  });
});
