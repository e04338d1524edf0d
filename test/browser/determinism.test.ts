/**
 * The random stream is a pure function of (pixel, sample index, seed,
 * dimension) and draws end on fixed multiples of the draw size, so the same
 * seed and spp give the same bits however render() calls are chunked.
 */
import { describe, expect, it } from 'vitest';
import { loadFixtureScene, useRenderSession } from '../support/browser';

describe('determinism', () => {
  const session = useRenderSession();
  const scene = loadFixtureScene('seed');
  const size = { width: 64, height: 48 };

  async function render(seed: number, chunks: number[]): Promise<Float32Array> {
    await session().load(scene, { ...size, seed });
    for (const chunk of chunks) await session().render(chunk);
    return session().readLinear();
  }

  it('gives identical bits for one seed however the samples are chunked, and other bits for another seed', async () => {
    const whole = await render(5, [24]);
    const chunked = await render(5, [1, 2, 13, 8]);
    const other = await render(6, [24]);
    expect(Buffer.from(chunked.buffer).equals(Buffer.from(whole.buffer))).toBe(true);
    expect(Buffer.from(other.buffer).equals(Buffer.from(whole.buffer))).toBe(false);
  });
});
