/**
 * The tiles of a sample pass (src/render/tiles.ts): every pixel in exactly
 * one tile, whole 2x2 quads, and runs of consecutive tiles spread over the
 * whole image (what lets the render loop predict a run's cost).
 */
import { describe, expect, it } from 'vitest';
import { TILE_WIDTH, TileLayout } from '../../src/render/tiles';

describe('TileLayout', () => {
  for (const [width, height] of [[1, 1], [2, 3], [157, 95], [512, 384], [64, 48], [1920, 1080], [7, 1]]) {
    it(`partitions ${width}x${height} into tiles of whole quads`, () => {
      const layout = new TileLayout(width, height);
      const covered = new Uint8Array(width * height);
      for (let u = 0; u < layout.count; u++) {
        const { x0, x1, y0, y1 } = layout.rect(u);
        expect(x1).toBeGreaterThan(x0);
        expect(y1).toBeGreaterThan(y0);
        expect(x0 % 2).toBe(0);
        expect(y0 % 2).toBe(0);
        expect(x1 % 2 === 0 || x1 === width).toBe(true);
        expect(y1 % 2 === 0 || y1 === height).toBe(true);
        for (let y = y0; y < y1; y++) for (let x = x0; x < x1; x++) covered[y * width + x]++;
      }
      expect(covered.every((c) => c === 1)).toBe(true);
      expect(layout.count).toBe(layout.rows * layout.segments);
      expect(layout.pixelsPerTile * layout.count).toBeCloseTo(width * height, 6);
    });
  }

  it('has tiles of two rows by about TILE_WIDTH columns', () => {
    const layout = new TileLayout(512, 384);
    expect(layout.rows).toBe(192);
    expect(layout.segments).toBe(512 / TILE_WIDTH);
    expect(layout.pixelsPerTile).toBe(256);
  });

  it('spreads any run of consecutive tiles over the image', () => {
    const layout = new TileLayout(512, 384);
    for (const run of [8, 32, 100]) {
      for (let first = 0; first + run <= layout.count; first += 37) {
        const rows = new Set<number>();
        const columns = new Set<number>();
        for (let u = first; u < first + run; u++) {
          const r = layout.rect(u);
          rows.add(r.y0 / 2);
          columns.add(r.x0);
        }
        // Rows: the run's tiles fall in distinct rows of tiles that cover the height
        // about evenly (each vertical eighth gets its share), and in every column segment.
        expect(rows.size).toBe(run);
        const eighths = new Array(8).fill(0);
        for (const row of rows) eighths[Math.floor((row / layout.rows) * 8)]++;
        for (const n of eighths) expect(n).toBeGreaterThanOrEqual(Math.floor(run / 8 / 2));
        expect(columns.size).toBe(layout.segments);
      }
    }
  });
});
