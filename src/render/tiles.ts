/**
 * Tiles of a sample pass: when one sample over the whole image is too much
 * work for one draw call (a frame budget, a GPU watchdog), the pass is drawn
 * in runs of tiles, and the sample counts once every tile is done.
 *
 * A tile is two pixel rows (one row of SwiftShader's 2x2 quads) by one column
 * segment (about TILE_WIDTH pixels, on even columns: no quad is split). Tiles
 * are numbered in an order that spreads any run of consecutive numbers over
 * the whole image: tile u is grid cell (u * step) mod count, row-major, with
 * step the integer nearest count / golden ratio^2 that is coprime with count
 * (a rank-1 lattice: a run of n tiles is n cells spaced about evenly over the
 * image, the three-distance theorem). So the cost of a run of tiles is about
 * that of any other run of the same length, even when the cost per pixel
 * varies a hundredfold over the image (a dense mesh in the middle, sky
 * around it): the render loop can predict the cost of its next draw from the
 * last ones. Runs also fall on many quad rows, which SwiftShader spreads over
 * its threads (they take quad rows in turn), and the first sample of a new
 * scene fills in over the whole image at once.
 *
 * The fragment shaders address pixels by gl_FragCoord only, so a pixel's sum
 * does not depend on which tile or draw computed it: a tiled pass gives the
 * same bits as a full-screen one. The vertex shader (fullscreen.vert) builds
 * the tiles' rectangles from gl_VertexID and the uniforms here.
 */

/** Target width of a column segment in pixels (a tile is 2 rows by about this many columns). */
export const TILE_WIDTH = 128;
/** The tile order's arithmetic stays in 32-bit unsigned integers (fullscreen.vert): count * step < 2^32. */
const MAX_TILES = 65535;

const gcd = (a: number, b: number): number => (b === 0 ? a : gcd(b, a % b));

/** A run of tiles to draw: `count` tiles from number `first` of `layout`. */
export interface TileRun {
  layout: TileLayout;
  first: number;
  count: number;
}

export class TileLayout {
  /** Rows of tiles: ceil(height / 2). */
  readonly rows: number;
  /** Column segments per row of tiles. */
  readonly segments: number;
  /** Tiles in the image: rows * segments. */
  readonly count: number;
  /** Multiplier of the order: tile u is cell (u * step) mod count. */
  readonly step: number;

  constructor(
    readonly width: number,
    readonly height: number,
  ) {
    this.rows = Math.ceil(height / 2);
    const wanted = Math.ceil(width / TILE_WIDTH);
    this.segments = Math.max(1, Math.min(wanted, Math.floor(width / 2), Math.floor(MAX_TILES / this.rows)));
    this.count = this.rows * this.segments;
    if (this.count > MAX_TILES) throw new Error(`an image ${height} pixels high has too many rows of tiles`);
    this.step = goldenStep(this.count);
  }

  /** Pixels per tile on average (tiles at the right and bottom edges may be smaller). */
  get pixelsPerTile(): number {
    return (this.width * this.height) / this.count;
  }

  /** The uniforms of fullscreen.vert that draw `run` (6 vertices per tile). */
  uniforms(run: TileRun): { uTiles: number[]; uTileTarget: number[] } {
    return { uTiles: [this.count, this.step, this.segments, run.first], uTileTarget: [this.width, this.height] };
  }

  /** The pixel rectangle [x0, x1) x [y0, y1) of tile `u` (as fullscreen.vert computes it; for tests). */
  rect(u: number): { x0: number; x1: number; y0: number; y1: number } {
    const cell = (u * this.step) % this.count;
    const y0 = Math.floor(cell / this.segments) * 2;
    const s = cell % this.segments;
    const edge = (k: number) => (k === this.segments ? this.width : Math.floor((k * this.width) / this.segments) & ~1);
    return { x0: edge(s), x1: edge(s + 1), y0, y1: Math.min(y0 + 2, this.height) };
  }
}

/** The integer nearest count / phi^2 (about 0.382 count) coprime with count. */
function goldenStep(count: number): number {
  if (count <= 2) return 1;
  const ideal = Math.round(count * (1 - 2 / (1 + Math.sqrt(5))));
  for (let d = 0; ; d++) {
    for (const m of [ideal - d, ideal + d]) {
      if (m >= 1 && m < count && gcd(m, count) === 1) return m;
    }
  }
}

/** Uniforms of fullscreen.vert for a full-screen draw (the one triangle). */
export const FULL_SCREEN = { uTiles: [0, 0, 0, 0], uTileTarget: [1, 1] };
