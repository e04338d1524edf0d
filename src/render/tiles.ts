/**
 * Tiles of a sample pass: when one sample over the whole image is too much
 * work for one draw call (a frame budget, a GPU watchdog), the pass is drawn
 * in runs of tiles, and the sample counts once every tile is done.
 *
 * A tile is a square of TILE_SIZE pixels, drawn as one point sprite
 * (gl_PointSize): one primitive, so no 2x2 quad is shaded twice, as quads
 * along the shared diagonal of two triangles would be (measured: a 2-row
 * rectangle drawn as two triangles costs 1.4-1.9x on SwiftShader with a
 * dense mesh). Squares at the right and top edges are moved inward to end at
 * the edge, overlapping their neighbours: a pixel drawn twice in a pass is
 * harmless, since every draw of the pass writes sums.read + the sample into
 * sums.write, the same value both times.
 *
 * Tiles are numbered in an order that spreads any run of consecutive numbers
 * over the whole image: tile u is grid cell (u * step) mod count, row-major,
 * a rank-1 lattice with the R2 sequence's generator (latticeStep). So the
 * cost of a run of tiles is about that of any other run of the same length,
 * even when the cost per pixel varies a hundredfold over the image (a dense
 * mesh in the middle, sky around it): with a disc of 100x cost over a
 * fifth of the image, every run of 16 tiles or more costs 0.4-1.7 times
 * the mean (test/unit/tiles.test.ts), where tiles row by row would cost
 * 0.04-3.6 times. The render loop can so predict the cost of its next draw from the
 * last ones. The first sample of a new scene also fills in over the whole
 * image at once.
 *
 * The fragment shaders address pixels by gl_FragCoord only, so a pixel's sum
 * does not depend on which tile or draw computed it: a tiled pass gives the
 * same bits as a full-screen one. fullscreen.vert places the tiles from
 * gl_VertexID and the uniforms here.
 */

/** Side of a tile in pixels (256 paths per sample; SwiftShader's 2x2 quads stay whole: even). */
export const TILE_SIZE = 16;
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
  /** Side of the tiles in pixels. */
  readonly size: number;
  /** Tiles per row and per column of the grid. */
  readonly columns: number;
  readonly rows: number;
  /** Tiles in the image: columns * rows. */
  readonly count: number;
  /** Multiplier of the order: tile u is cell (u * step) mod count. */
  readonly step: number;

  /** `maxPointSize`: the largest point sprite the context draws (ALIASED_POINT_SIZE_RANGE). */
  constructor(
    readonly width: number,
    readonly height: number,
    maxPointSize = 1024,
  ) {
    let size = TILE_SIZE;
    // Larger tiles for a huge image, so that their count fits the order's arithmetic.
    while (Math.ceil(width / size) * Math.ceil(height / size) > MAX_TILES) size += 2;
    size = Math.min(size, width, height, Math.floor(maxPointSize));
    this.size = Math.max(1, size);
    this.columns = Math.ceil(width / this.size);
    this.rows = Math.ceil(height / this.size);
    this.count = this.columns * this.rows;
    this.step = this.usable ? latticeStep(this.columns, this.rows) : 1;
  }

  /**
   * False when the context's points are too small for tiles of this image
   * (ALIASED_POINT_SIZE_RANGE may be as low as 1): samples are then drawn
   * whole.
   */
  get usable(): boolean {
    return this.count <= MAX_TILES;
  }

  /** Pixels per tile on average (tiles at the edges overlap their neighbours). */
  get pixelsPerTile(): number {
    return (this.width * this.height) / this.count;
  }

  /** The uniforms of fullscreen.vert that draw `run` (one point per tile). */
  uniforms(run: TileRun): { uTiles: number[]; uTileGrid: number[] } {
    return { uTiles: [this.count, this.step, this.columns, run.first], uTileGrid: [this.size, this.width, this.height] };
  }

  /** The pixel square [x0, x0 + size) x [y0, y0 + size) of tile `u`, as fullscreen.vert places it (for tests). */
  rect(u: number): { x0: number; y0: number; size: number } {
    const cell = (u * this.step) % this.count;
    const x0 = Math.min((cell % this.columns) * this.size, this.width - this.size);
    const y0 = Math.min(Math.floor(cell / this.columns) * this.size, this.height - this.size);
    return { x0, y0, size: this.size };
  }
}

/**
 * The multiplier of the tile order: cell (u * step) mod count, row-major.
 * Near the generator of the R2 sequence (a step of 0.7549 columns and 0.5698
 * rows: 1 / the plastic number and its square), whose runs cover a square
 * evenly in 2D, the candidate coprime with count (so that the order visits
 * every cell once) whose first RUN multiples are farthest from the first
 * cell: consecutive tiles are never close. (The 1D golden ratio on
 * row-major cells leaves runs in a few columns when the grid is wide.)
 */
function latticeStep(columns: number, rows: number): number {
  const count = columns * rows;
  if (count <= 2) return 1;
  const RUN = 8;
  const separation = (step: number) => {
    let nearest = Infinity;
    for (let k = 1; k <= RUN; k++) {
      const cell = (k * step) % count;
      const dx = (cell % columns) / columns;
      const dy = Math.floor(cell / columns) / rows;
      // Toroidal distance, in units of the image width.
      nearest = Math.min(nearest, Math.hypot(Math.min(dx, 1 - dx), (Math.min(dy, 1 - dy) * rows) / columns));
    }
    return nearest;
  };
  let best = 1;
  let bestSeparation = -1;
  for (let dx = -4; dx <= 4; dx++) {
    for (let dy = -4; dy <= 4; dy++) {
      const ax = Math.round(0.7548776662 * columns) + dx;
      const ay = Math.round(0.569840291 * rows) + dy;
      const step = (((ay * columns + ax) % count) + count) % count;
      if (step < 1 || gcd(step, count) !== 1) continue;
      const s = separation(step);
      if (s > bestSeparation) {
        best = step;
        bestSeparation = s;
      }
    }
  }
  return best;
}

/** Uniforms of fullscreen.vert for a full-screen draw (the one triangle). */
export const FULL_SCREEN = { uTiles: [0, 0, 0, 0], uTileGrid: [1, 1, 1] };
