/**
 * The tiles of a sample pass (src/render/tiles.ts): together they cover
 * every pixel (squares at the edges overlap their neighbours, nothing else
 * does), they keep SwiftShader's 2x2 quads whole, and runs of consecutive
 * tiles are spread over the whole image (what lets the render loop predict
 * a run's cost).
 */
import { describe, expect, it } from 'vitest';
import { TILE_SIZE, TileLayout } from '../../src/render/tiles';

describe('TileLayout', () => {
  for (const [width, height] of [[1, 1], [2, 3], [157, 95], [512, 384], [64, 48], [1920, 1080], [7, 1], [100, 20]]) {
    it(`covers ${width}x${height} with squares`, () => {
      const layout = new TileLayout(width, height);
      expect(layout.usable).toBe(true);
      const covered = new Uint8Array(width * height);
      for (let u = 0; u < layout.count; u++) {
        const { x0, y0, size } = layout.rect(u);
        expect(x0).toBeGreaterThanOrEqual(0);
        expect(y0).toBeGreaterThanOrEqual(0);
        expect(x0 + size).toBeLessThanOrEqual(width);
        expect(y0 + size).toBeLessThanOrEqual(height);
        for (let y = y0; y < y0 + size; y++) for (let x = x0; x < x0 + size; x++) covered[y * width + x]++;
      }
      expect(covered.every((c) => c >= 1)).toBe(true);
      // Overlaps only in the last column and row of tiles.
      const { size } = layout;
      for (let y = 0; y < height; y++) {
        for (let x = 0; x < width; x++) {
          if (covered[y * width + x] > 1) expect(x >= width - size || y >= height - size, `pixel ${x},${y}`).toBe(true);
        }
      }
      expect(new Set(Array.from({ length: layout.count }, (_, u) => (u * layout.step) % layout.count)).size).toBe(layout.count);
    });
  }

  it(`has squares of ${TILE_SIZE} pixels, whole quads, and 256 paths each at 512x384`, () => {
    const layout = new TileLayout(512, 384);
    expect(layout.size).toBe(TILE_SIZE);
    expect(TILE_SIZE % 2).toBe(0);
    expect([layout.columns, layout.rows]).toEqual([32, 24]);
    expect(layout.pixelsPerTile).toBe(256);
    for (let u = 0; u < layout.count; u++) expect(layout.rect(u).x0 % 2 + (layout.rect(u).y0 % 2)).toBe(0);
  });

  it('grows the squares for huge images, and gives up when points cannot be that large', () => {
    const huge = new TileLayout(8192, 8192);
    expect(huge.usable).toBe(true);
    expect(huge.size).toBeGreaterThan(TILE_SIZE);
    expect(huge.count).toBeLessThanOrEqual(65535);
    expect(new TileLayout(8192, 8192, 16).usable).toBe(false);
    expect(new TileLayout(512, 384, 1).usable).toBe(false);
    expect(new TileLayout(200, 200, 1).usable).toBe(true); // 1x1 points: 40000 tiles
  });

  // A disc of 100x the cost over about a fifth of the image (a dense mesh framed in the middle, sky around it).
  for (const [width, height] of [[512, 384], [864, 544], [1920, 1080]]) {
    it(`gives every run of tiles about the mean cost at ${width}x${height}`, () => {
      const layout = new TileLayout(width, height);
      const cost = (u: number) => {
        const { x0, y0, size } = layout.rect(u);
        const dx = (x0 + size / 2) / width - 0.5;
        const dy = ((y0 + size / 2) / height - 0.5) * (height / width);
        return Math.hypot(dx, dy) < 0.25 ? 100 : 1;
      };
      const costs = Array.from({ length: layout.count }, (_, u) => cost(u));
      const mean = costs.reduce((a, b) => a + b, 0) / layout.count;
      // Bounds: a run of 8 holds ~1.6 disc tiles on average, so one more or less is already -40%/+60%.
      const bounds: Record<number, [number, number]> = { 8: [0, 2.1], 16: [0.4, 1.7], 64: [0.6, 1.35] };
      for (const run of [8, 16, 64]) {
        let low = Infinity;
        let high = 0;
        for (let first = 0; first + run <= layout.count; first++) {
          let sum = 0;
          for (let u = first; u < first + run; u++) sum += costs[u];
          low = Math.min(low, sum / run / mean);
          high = Math.max(high, sum / run / mean);
        }
        expect(high, `run of ${run}`).toBeLessThan(bounds[run][1]);
        expect(low, `run of ${run}`).toBeGreaterThanOrEqual(bounds[run][0]);
      }
    });
  }
});
