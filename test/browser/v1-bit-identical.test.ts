/**
 * Version-1 documents render bit-identically through the version-2 code: the
 * fixtures in test/fixtures/v1-renders were rendered by commit 60db06a (the
 * last build before the restructure, with its own parser) at a fixed size,
 * spp and seed by scripts/make-v1-renders.ts, on SwiftShader as CI runs.
 * The same render with the current build must give the same float32 bits
 * (PFM stores float32 exactly); no tolerance, because the restructure claims
 * to change nothing for these scenes.
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { decodePfm } from '../../src/image/pfm';
import { FIXTURES, loadFixtureScene, useRenderSession } from '../support/browser';
import { V1_RENDER, V1_SCENES } from '../../scripts/make-v1-renders';

describe('version-1 scenes render bit-identically to 60db06a', () => {
  const session = useRenderSession();

  for (const name of V1_SCENES) {
    it(name, async () => {
      const { width, height, spp, seed } = V1_RENDER;
      const old = decodePfm(readFileSync(new URL(`v1-renders/${name}.pfm`, FIXTURES)));
      expect([old.width, old.height]).toEqual([width, height]);
      await session().load(loadFixtureScene(name), { width, height, seed });
      await session().render(spp);
      const now = await session().readLinear();
      let differing = 0;
      let firstDifference = '';
      for (let p = 0; p < width * height; p++) {
        for (let c = 0; c < 3; c++) {
          const a = now[p * 4 + c];
          const b = old.rgb[p * 3 + c];
          if (Object.is(a, b)) continue;
          if (differing++ === 0) firstDifference = `pixel (${p % width}, ${Math.floor(p / width)}) channel ${c}: ${a} now, ${b} at 60db06a`;
        }
      }
      expect(differing, `${differing} of ${width * height * 3} floats differ; first: ${firstDifference}`).toBe(0);
      // Guards against a vacuous pass: the fixture is a real image.
      expect(old.rgb.some((v) => v > 0)).toBe(true);
    });
  }
});
