/**
 * How many paths the render loop traces in a frame: as many as fit a time
 * budget, from the measured cost per path of recent frames. A dense mesh on
 * a slow GPU gets a part of a sample per frame (PathTracer.renderPaths draws
 * it in tiles); a fast GPU gets many samples.
 *
 * Measurements arrive a few frames late (GPU timer queries) or describe the
 * frame before (frame gaps), and are noisy: the runs of tiles drawn differ
 * in cost, a loaded machine stalls a frame now and then (on the 2-core
 * reference machine loaded by other jobs, about one measurement in five is
 * 3-10x the others), and the first draw of a program includes its compile
 * (SwiftShader compiles at the first draw). So:
 * - the cost per path is the median of the last 5 measurements: two
 *   outliers move nothing, three agreeing ones do; until 3 measurements of
 *   the current scene have come in, the paths per frame stay at the start.
 *   A median above the estimate is taken at once (a heavier view must not
 *   keep making long frames); below, the estimate moves half way there (in
 *   log space) per measurement, against jitter;
 * - between measurements the paths per frame stay as they are, and they grow
 *   to at most GROWTH times the paths of the frame measured, so late
 *   measurements of small frames cannot compound into a huge one;
 * - after a change that may change the cost a lot (restart(): meshes added
 *   or moved, materials, bounces), the cost is unknown: frames start at
 *   `startPaths` and grow from measurements of the new scene only. Until
 *   the first estimate, frame gaps, which come a frame or two late, double
 *   the paths per frame while frames are quick (25 ms: a cheap scene
 *   then reaches its size in a few frames, not after the timer's 3-8 frames
 *   of lag times several growth steps); the gaps are the whole frame, an
 *   upper bound of the work, so this never grows a heavy scene.
 */

export interface PathBudgetOptions {
  /** Milliseconds of work to aim at per frame. */
  targetMs: number;
  /** Paths per frame after restart(), until the cost is measured. */
  startPaths: number;
  minPaths: number;
  maxPaths: number;
}

/** Most growth of the paths per frame over the paths of a measured frame. */
export const GROWTH = 3;
/** Measurements the median is taken over. */
const WINDOW = 5;
/** The fraction of the way (in log space) the estimate moves down to a lower median per measurement. */
const DOWN_GAIN = 1 / 2;
/** Measurements of a scene before the first estimate of its cost. */
const FIRST = 3;
/** A frame gap that leaves room for more work: up to one and a half 60 Hz frames. */
const QUICK_FRAME_MS = 25;

export class PathBudget {
  private msPerPath: number | null = null;
  /** The last WINDOW measurements of the cost per path, oldest first. */
  private recent: number[] = [];
  private current: number;

  constructor(private options: PathBudgetOptions) {
    this.current = options.startPaths;
  }

  /** Paths to trace in the next frame. */
  get paths(): number {
    return this.current;
  }

  /** The estimated cost of a path in milliseconds, or null before the first measurement. */
  get costPerPath(): number | null {
    return this.msPerPath;
  }

  /** Changes the bounds and target (e.g. a new image size); keeps the estimate. */
  setOptions(options: PathBudgetOptions): void {
    this.options = options;
    this.current = this.clamp(this.current);
  }

  /** `ms` of work measured for a frame that traced `paths` paths. */
  observe(ms: number, paths: number): void {
    if (!(paths > 0) || !(ms >= 0) || !Number.isFinite(ms)) return;
    this.recent.push(Math.max(ms, 1e-3) / paths);
    if (this.recent.length > WINDOW) this.recent.shift();
    if (this.recent.length < FIRST) return;
    const sorted = [...this.recent].sort((a, b) => a - b);
    // With an even count, the larger middle one: cautious.
    const median = sorted[Math.floor(sorted.length / 2)];
    if (this.msPerPath === null || median > this.msPerPath) this.msPerPath = median;
    else this.msPerPath *= (median / this.msPerPath) ** DOWN_GAIN;
    // Grows from what was measured (or keeps its size: late measurements of small frames do not shrink it either).
    this.current = this.clamp(Math.min(this.options.targetMs / this.msPerPath, Math.max(paths * GROWTH, this.current)));
  }

  /**
   * A frame gap of `ms` after a frame that traced `paths` paths: doubles the
   * paths per frame when the frame was quick (QUICK_FRAME_MS), until the
   * cost is estimated (observe).
   */
  observeGap(ms: number, paths: number): void {
    if (this.msPerPath !== null || !(ms > 0) || paths < this.current / 2) return;
    if (ms <= Math.min(QUICK_FRAME_MS, this.options.targetMs)) this.current = this.clamp(this.current * 2);
  }

  /** Forgets the cost: the scene changed in a way that may change it a lot. */
  restart(): void {
    this.msPerPath = null;
    this.recent = [];
    this.current = this.clamp(this.options.startPaths);
  }

  private clamp(paths: number): number {
    return Math.max(this.options.minPaths, Math.min(this.options.maxPaths, paths));
  }
}
