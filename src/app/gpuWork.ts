/**
 * What the render loop knows of the GPU's progress without stalling it:
 * how long its draws took (timer queries, read a few frames later) and how
 * much of its work is still in flight (fences).
 */

/** GPU time of the render calls, read back a few frames later without stalling. */
export class GpuTimer {
  private readonly ext: { TIME_ELAPSED_EXT: number; GPU_DISJOINT_EXT: number } | null;
  private pending: { query: WebGLQuery; paths: number }[] = [];

  constructor(private readonly gl: WebGL2RenderingContext) {
    this.ext = gl.getExtension('EXT_disjoint_timer_query_webgl2');
  }

  get available(): boolean {
    return this.ext !== null;
  }

  /** Runs `work` (which returns the paths it traced), timed when a query is free. */
  measure(work: () => number): number {
    const gl = this.gl;
    const query = this.ext && this.pending.length < 8 ? gl.createQuery() : null;
    if (!query || !this.ext) return work();
    gl.beginQuery(this.ext.TIME_ELAPSED_EXT, query);
    const paths = work();
    gl.endQuery(this.ext.TIME_ELAPSED_EXT);
    if (paths > 0) this.pending.push({ query, paths });
    else gl.deleteQuery(query);
    return paths;
  }

  /** The finished measurements, oldest first: milliseconds of GPU time for `paths` paths. */
  poll(): { ms: number; paths: number }[] {
    const gl = this.gl;
    const results: { ms: number; paths: number }[] = [];
    if (!this.ext) return results;
    while (this.pending.length && gl.getQueryParameter(this.pending[0].query, gl.QUERY_RESULT_AVAILABLE)) {
      const { query, paths } = this.pending.shift()!;
      const disjoint = gl.getParameter(this.ext.GPU_DISJOINT_EXT) as boolean;
      const nanoseconds = gl.getQueryParameter(query, gl.QUERY_RESULT) as number;
      gl.deleteQuery(query);
      if (!disjoint) results.push({ ms: nanoseconds / 1e6, paths });
    }
    return results;
  }

  /** Drops the measurements not read yet (they are of a scene that changed). */
  discard(): void {
    this.pending.forEach(({ query }) => this.gl.deleteQuery(query));
    this.pending = [];
  }

  /** Forgets the queries of a lost context (they died with it). */
  reset(): void {
    this.pending = [];
  }
}

/** Fences after submitted work: WebGL2's fenceSync in the page, synthetic ones in tests. */
export interface FenceSource<F> {
  /** A fence after the work submitted so far, or null when none can be made. */
  insert(): F | null;
  /** Whether the GPU is known to have passed `fence` (in a browser: some time after it did). */
  passed(fence: F): boolean;
  /** Frees a fence. */
  remove(fence: F): void;
}

/** WebGL2 fences. Their status changes only between tasks, a little after the GPU passed them. */
export function webglFences(gl: WebGL2RenderingContext): FenceSource<WebGLSync> {
  return {
    insert: () => gl.fenceSync(gl.SYNC_GPU_COMMANDS_COMPLETE, 0),
    passed: (fence) => gl.getSyncParameter(fence, gl.SYNC_STATUS) === gl.SIGNALED,
    remove: (fence) => gl.deleteSync(fence),
  };
}

/**
 * The loop's work in the GPU's queue: what was submitted and is not yet seen
 * done, as the milliseconds of work predicted for it (from the budget's cost
 * per path), bounded by fences, one after each frame's work.
 *
 * Why fences and not a prediction from the submission times: the work does
 * not start when it is submitted. Measured headless on SwiftShader (GPU
 * timestamps against the page's clock and Chromium traces,
 * bench/results/frame-pacing-2026-12-06.md), a frame's work began 100-260 ms
 * after it was submitted while a prediction that started it at once said the
 * queue was empty; the page's commands reached the GPU late and in batches of
 * 3-5 frames, and the compositor frame that follows such a batch (which reads
 * the page back, after all work queued before it) was a frame of 100-180 ms.
 * A fence is seen passed 2-15 ms after its work is done (when the page does
 * not repaint every frame: a repaint is a compositor frame that keeps the GPU
 * process busy), so the work in flight is known, late only by that, wherever
 * it waits. A GPU that runs behind (software, loaded, slow) is then never
 * given more than `limit` of work ahead: the compositor, a read-back, an
 * input's redraw wait at most for that.
 */
export class GpuQueue<F = WebGLSync> {
  private inflight: { fence: F; ms: number; polls: number }[] = [];

  /**
   * @param maxPolls polls after which a fence not seen passed is taken as
   * passed anyway: a browser whose fences never signal must not stop the
   * loop for good (600 polls are 10 s of frames at 60 Hz; a frame of
   * SwiftShader's slowest work, a compile at the first draw, is a few seconds).
   */
  constructor(
    private readonly fences: FenceSource<F>,
    private readonly maxPolls = 600,
  ) {}

  /** Forgets the work the GPU is seen to have done; returns the milliseconds of work still in flight. */
  poll(): number {
    // Fences pass in order: the newest one passed means all before it passed too.
    for (let i = this.inflight.length - 1; i >= 0; i--) {
      if (!this.fences.passed(this.inflight[i].fence) && ++this.inflight[i].polls <= this.maxPolls) continue;
      for (const { fence } of this.inflight.splice(0, i + 1)) this.fences.remove(fence);
      break;
    }
    return this.pendingMs;
  }

  /** Milliseconds of work in flight as of the last poll (and submissions since). */
  get pendingMs(): number {
    return this.inflight.reduce((sum, f) => sum + f.ms, 0);
  }

  /** Work predicted to take `ms` was just submitted. Without a fence it is not counted (nothing would say when it is done). */
  submitted(ms: number): void {
    const fence = this.fences.insert();
    if (fence !== null) this.inflight.push({ fence, ms, polls: 0 });
  }

  /** Forgets the work in flight; its fences are freed unless they died with a lost context. */
  reset(lost = false): void {
    if (!lost) this.inflight.forEach(({ fence }) => this.fences.remove(fence));
    this.inflight = [];
  }
}

/**
 * The paths to submit in a frame: the budget's, as far as the work in flight
 * leaves room under `limitMs`. Without an estimated cost per path, a frame
 * counts as `frameMs` and goes only when the room holds a whole one. A
 * little room is left unused (fewer than `leastPaths`, or the budget's paths
 * if fewer): small frames fill the queue as well, in more draws.
 */
export function pathsWithRoom(options: {
  budgetPaths: number;
  costPerPath: number | null;
  pendingMs: number;
  limitMs: number;
  frameMs: number;
  leastPaths: number;
}): number {
  const { budgetPaths, costPerPath, pendingMs, limitMs, frameMs, leastPaths } = options;
  const room = limitMs - pendingMs;
  if (costPerPath === null || !(costPerPath > 0)) return room >= frameMs ? budgetPaths : 0;
  const paths = Math.min(budgetPaths, Math.floor(room / costPerPath));
  return paths >= Math.min(budgetPaths, leastPaths) && paths > 0 ? paths : 0;
}
