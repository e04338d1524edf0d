/**
 * What the render loop knows of the GPU's progress without stalling it:
 * how long its draws took (timer queries, read a few frames later) and how
 * much work is still queued (predicted).
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

/**
 * The GPU's queue of the loop's work, as predicted from the cost per path:
 * the GPU runs behind the page (a slow GPU, a software one on a loaded
 * CPU), and if the page kept submitting a frame's work every frame, work
 * would pile up, and whatever waits for the GPU (the compositor, a
 * read-back) would wait for all of it. Fences or query results would tell
 * when work is done, but in Chrome they arrive several frames late (the
 * loop skipped most frames with a fence per frame, the GPU idle 80% of the
 * time); the prediction is immediate, and as good as the budget's estimate.
 */
export class GpuQueue {
  /** When (performance.now() ms) the GPU is predicted to finish the work submitted. */
  private idleAt = 0;

  /** Milliseconds of submitted work predicted to be still queued at `now`. */
  backlog(now: number): number {
    return Math.max(0, this.idleAt - now);
  }

  /** Work predicted to take `ms` was submitted at `now`. */
  submitted(now: number, ms: number): void {
    this.idleAt = Math.max(this.idleAt, now) + ms;
  }

  /** Forgets the queue (a lost context, a scene whose cost is not known). */
  reset(): void {
    this.idleAt = 0;
  }
}

/**
 * The loop's work the GPU has not yet been seen to finish: a fence after each
 * frame's work, polled every frame (the status of a fence changes only
 * between tasks, some time after the GPU passed it).
 */
export class GpuFences {
  private inflight: { sync: WebGLSync; ms: number }[] = [];

  constructor(private gl: WebGL2RenderingContext) {}

  /** Milliseconds of predicted work submitted and not seen finished. */
  get pendingMs(): number {
    return this.inflight.reduce((sum, f) => sum + f.ms, 0);
  }

  get pending(): number {
    return this.inflight.length;
  }

  /** Drops the fences passed: a signaled fence means every earlier one is passed too. */
  poll(): void {
    const gl = this.gl;
    for (let i = this.inflight.length - 1; i >= 0; i--) {
      if (gl.getSyncParameter(this.inflight[i].sync, gl.SYNC_STATUS) === gl.SIGNALED) {
        for (const f of this.inflight.slice(0, i + 1)) gl.deleteSync(f.sync);
        this.inflight = this.inflight.slice(i + 1);
        return;
      }
    }
  }

  /** Work predicted to take `ms` has just been submitted. */
  submitted(ms: number): void {
    const sync = this.gl.fenceSync(this.gl.SYNC_GPU_COMMANDS_COMPLETE, 0);
    if (sync) this.inflight.push({ sync, ms });
  }

  reset(gl: WebGL2RenderingContext = this.gl): void {
    if (!this.gl.isContextLost()) this.inflight.forEach((f) => this.gl.deleteSync(f.sync));
    this.gl = gl;
    this.inflight = [];
  }
}
