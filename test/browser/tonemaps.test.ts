/**
 * The displayed image's tone maps (ACES, Khronos PBR Neutral, AgX in
 * src/shaders/display.frag) against known values from independent TypeScript
 * implementations of their published definitions
 * (test/support/toneMapReference.ts), through readDisplayed: the camera sees
 * only a constant environment (no geometry), so every pixel's linear value is
 * exactly the environment's radiance, scaled by 2^exposure before the tone
 * map. Inputs span the toe, the linear part and the shoulder (2^-6 to 2^5
 * times the colour) with unequal channels, so a swapped matrix
 * (row- vs column-major) shows too.
 * Tolerance: 1 step of 8 bits; float32 evaluation on the GPU and
 * SwiftShader's pow/log2 approximations (~1e-4 relative) cannot move a
 * value by more than that, while a wrong constant or matrix order moves
 * it by many steps (checked below: the tone maps differ from each other and
 * from no tone map by far more).
 */
import { describe, expect, it } from 'vitest';
import { parseScene } from '../../src/scene/schema';
import { useRenderSession } from '../support/browser';
import { acesHill, agxMinimal, khronosNeutral, srgb8 } from '../support/toneMapReference';

type Rgb = [number, number, number];
const REFERENCES: Record<string, (c: Rgb) => Rgb> = { aces: acesHill, neutral: khronosNeutral, agx: agxMinimal, none: (c) => c };
const COLORS: Rgb[] = [[1, 0.3, 0.05], [0.05, 0.4, 1]];
const EXPOSURES = [-6, -2, 0, 1, 3, 5];

describe('tone maps match independent implementations of their definitions', () => {
  const session = useRenderSession();

  for (const color of COLORS) {
    it(`environment ${JSON.stringify(color)} at exposures ${EXPOSURES.join(', ')}`, async () => {
      const scene = parseScene({ camera: { position: [0, 0, 0], target: [0, 0, -1] }, environment: { color, intensity: 1 }, spheres: [], lights: [] });
      await session().load(scene, { width: 4, height: 4, seed: 1 });
      await session().render(1);
      const failures: string[] = [];
      const seen = new Map<string, string>();
      for (const exposure of EXPOSURES) {
        const input = color.map((c) => c * 2 ** exposure) as Rgb;
        for (const [tonemap, reference] of Object.entries(REFERENCES)) {
          const pixels = await session().readDisplayed({ exposure, toneMap: tonemap });
          const expected = reference(input).map(srgb8);
          const actual = [pixels[0], pixels[1], pixels[2]];
          seen.set(`${exposure}/${tonemap}`, actual.join(','));
          // Every pixel shows the same value.
          for (let p = 0; p < pixels.length; p += 4) {
            if (pixels[p] !== actual[0] || pixels[p + 1] !== actual[1] || pixels[p + 2] !== actual[2]) failures.push(`${tonemap} e=${exposure}: pixel ${p / 4} differs from pixel 0`);
          }
          if (actual.some((v, i) => Math.abs(v - expected[i]) > 1)) {
            failures.push(`${tonemap} at input ${input.map((v) => v.toPrecision(4)).join(',')}: displayed ${actual}, expected ${expected}`);
          }
        }
      }
      expect(failures).toEqual([]);
      // The tone maps really are different curves at the shoulder (not one
      // curve under four names).
      const atShoulder = ['aces', 'neutral', 'agx', 'none'].map((t) => seen.get(`3/${t}`));
      expect(new Set(atShoulder).size, JSON.stringify(atShoulder)).toBe(4);
    });
  }
});
