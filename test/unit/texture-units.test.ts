/** The texture-unit registry (src/render/gl/textureUnits.ts): every unit distinct and within WebGL2's guaranteed 16. */
import { describe, expect, it } from 'vitest';
import { ENVIRONMENT_UNITS, TEXTURE_UNITS } from '../../src/render/gl/textureUnits';

describe('TEXTURE_UNITS', () => {
  it('names each unit once', () => {
    const units = Object.values(TEXTURE_UNITS);
    expect(new Set(units).size).toBe(units.length);
  });

  it('uses only the units WebGL2 guarantees', () => {
    for (const unit of Object.values(TEXTURE_UNITS)) {
      expect(Number.isInteger(unit)).toBe(true);
      expect(unit).toBeGreaterThanOrEqual(0);
      expect(unit).toBeLessThan(16);
    }
  });

  it('gives the environment map its own units', () => {
    expect(ENVIRONMENT_UNITS).toEqual({ map: TEXTURE_UNITS.environmentMap, marginal: TEXTURE_UNITS.environmentMarginal, conditional: TEXTURE_UNITS.environmentConditional });
  });
});
