/**
 * Image orientation end to end: a light placed right of and above the view
 * centre must appear right and up in the PNG the CLI writes (the same
 * readDisplayed + encodePng path), and in the linear read-back.
 */
import { describe, expect, it } from 'vitest';
import { decodePng, encodePng } from '../../src/cli/png';
import { parseScene } from '../../src/scene/schema';
import { useRenderSession } from '../support/browser';

const scene = parseScene({
  camera: { position: [0, 0, 10], target: [0, 0, 0], up: [0, 1, 0], fov: 40 },
  image: { width: 96, height: 64 },
  render: { maxBounces: 1 },
  // Right (+x) and up (+y) of the view centre, seen from +z looking at -z.
  lights: [{ position: [2, 1.2, 0], radius: 0.4, intensity: 1 }],
  spheres: [{ center: [-2, -1.2, 0], radius: 0.4, material: { color: [0.1, 0.1, 0.1] } }],
});

function brightCentroid(values: (p: number) => number, width: number, height: number) {
  let sx = 0;
  let sy = 0;
  let n = 0;
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      if (values(y * width + x) > 0.5) {
        sx += x;
        sy += y;
        n++;
      }
    }
  }
  return { x: sx / n, y: sy / n, n };
}

describe('orientation', () => {
  const session = useRenderSession();

  it('puts an object right of and above the centre right and up in the PNG', async () => {
    await session().load(scene, { width: 96, height: 64, seed: 0 });
    await session().render(4);
    const png = decodePng(encodePng(96, 64, await session().readDisplayed({ exposure: 0, toneMap: 'none' })));
    const c = brightCentroid((p) => png.rgba[p * 4] / 255, png.width, png.height);
    expect(c.n).toBeGreaterThan(10);
    expect(c.x).toBeGreaterThan(png.width / 2 + 10);
    expect(c.y).toBeLessThan(png.height / 2 - 5); // row 0 is the top

    const linear = await session().readLinear();
    const l = brightCentroid((p) => linear[p * 4], 96, 64);
    expect(Math.abs(l.x - c.x)).toBeLessThan(1);
    expect(Math.abs(l.y - c.y)).toBeLessThan(1);
  });
});
