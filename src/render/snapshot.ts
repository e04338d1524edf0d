/**
 * Keeps a recent copy of a PathTracer's running sums in CPU memory, so a
 * lost WebGL context (GPU reset, watchdog, a background tab reclaimed)
 * resumes from the image it had instead of from zero.
 *
 * The copy is read back without stalling the render: readPixels into a pixel
 * buffer object plus a fence, then the buffer is only read once the fence has
 * signalled (a later frame). At most one read-back is in flight. The sums are
 * those of the same sample indices in the same order, so resuming from a
 * snapshot of n samples and adding more gives the same image as an
 * uninterrupted render (the random streams depend only on pixel, sample
 * index and seed); only the samples after the last snapshot are redone.
 */
import type { PathTracer } from './PathTracer';

export interface AccumulationSnapshot {
  sums: Float32Array;
  samples: number;
  generation: number;
  width: number;
  height: number;
}

interface PendingReadback {
  buffer: WebGLBuffer;
  sync: WebGLSync;
  samples: number;
  generation: number;
  width: number;
  height: number;
}

/** Default interval between snapshots. */
export const SNAPSHOT_INTERVAL_MS = 2000;

export class SnapshotKeeper {
  private latest: AccumulationSnapshot | null = null;
  private pending: PendingReadback | null = null;
  private lastStart = -Infinity;
  private readonly unsubscribe: (() => void)[];

  constructor(
    private readonly tracer: PathTracer,
    private readonly intervalMs = SNAPSHOT_INTERVAL_MS,
  ) {
    this.unsubscribe = [
      // The buffer and fence died with the context.
      tracer.on('contextlost', () => (this.pending = null)),
      tracer.on('contextrestored', () => this.resume()),
    ];
  }

  /** The most recent complete snapshot (for tests and statistics). */
  get snapshot(): AccumulationSnapshot | null {
    return this.latest;
  }

  /**
   * Call once per frame, after rendering: finishes a read-back whose fence
   * has signalled, and starts a new one when the interval has passed and
   * there are new samples to keep.
   */
  tick(now = performance.now()): void {
    const state = this.tracer.accumulation();
    if (!state) return;
    if (this.pending) this.collect();
    if (this.latest && this.latest.generation !== state.generation) this.latest = null; // a restart made it stale
    if (this.pending || now - this.lastStart < this.intervalMs) return;
    if (state.samples === 0 || state.samples === this.latest?.samples) return;
    this.start(state);
    this.lastStart = now;
  }

  /**
   * Takes a snapshot now, reading back synchronously: for when the page is
   * being hidden (a background tab is where contexts get reclaimed, and no
   * later frame would collect an asynchronous read-back).
   */
  captureNow(): void {
    const state = this.tracer.accumulation();
    if (!state || state.samples === 0 || (this.latest?.samples === state.samples && this.latest.generation === state.generation)) return;
    const gl = this.tracer.gl;
    this.drop();
    const sums = new Float32Array(state.width * state.height * 4);
    gl.bindFramebuffer(gl.FRAMEBUFFER, state.framebuffer);
    gl.readPixels(0, 0, state.width, state.height, gl.RGBA, gl.FLOAT, sums);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    const { samples, generation, width, height } = state;
    this.latest = { sums, samples, generation, width, height };
    this.lastStart = performance.now();
  }

  dispose(): void {
    this.unsubscribe.forEach((off) => off());
    this.drop();
  }

  private start(state: NonNullable<ReturnType<PathTracer['accumulation']>>): void {
    const gl = this.tracer.gl;
    const buffer = gl.createBuffer();
    if (!buffer) return;
    gl.bindBuffer(gl.PIXEL_PACK_BUFFER, buffer);
    gl.bufferData(gl.PIXEL_PACK_BUFFER, state.width * state.height * 16, gl.STREAM_READ);
    gl.bindFramebuffer(gl.FRAMEBUFFER, state.framebuffer);
    gl.readPixels(0, 0, state.width, state.height, gl.RGBA, gl.FLOAT, 0);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.bindBuffer(gl.PIXEL_PACK_BUFFER, null);
    const sync = gl.fenceSync(gl.SYNC_GPU_COMMANDS_COMPLETE, 0);
    if (!sync) {
      gl.deleteBuffer(buffer);
      return;
    }
    gl.flush();
    const { samples, generation, width, height } = state;
    this.pending = { buffer, sync, samples, generation, width, height };
  }

  private collect(): void {
    const gl = this.tracer.gl;
    const p = this.pending!;
    if (gl.getSyncParameter(p.sync, gl.SYNC_STATUS) !== gl.SIGNALED) return;
    const sums = new Float32Array(p.width * p.height * 4);
    gl.bindBuffer(gl.PIXEL_PACK_BUFFER, p.buffer);
    gl.getBufferSubData(gl.PIXEL_PACK_BUFFER, 0, sums);
    gl.bindBuffer(gl.PIXEL_PACK_BUFFER, null);
    this.drop();
    this.latest = { sums, samples: p.samples, generation: p.generation, width: p.width, height: p.height };
  }

  private drop(): void {
    const p = this.pending;
    this.pending = null;
    if (!p || this.tracer.gl.isContextLost()) return;
    this.tracer.gl.deleteSync(p.sync);
    this.tracer.gl.deleteBuffer(p.buffer);
  }

  private resume(): void {
    const s = this.latest;
    if (!s || !this.tracer.restoreAccumulation(s.sums, s.samples, s.generation, s.width, s.height)) this.latest = null;
  }
}
