/**
 * The progressive render loop: every animation frame adds samples, sized to
 * a frame-time budget, and shows the running mean. Samples per frame adapt:
 * from GPU timer queries (EXT_disjoint_timer_query_webgl2) when the browser
 * has them, else from the frame-to-frame time, so input and UI stay above
 * 30 fps while a fast GPU gets many samples per frame.
 */
import type { PathTracer } from '../render/PathTracer';
import type { ToneMap } from '../render/toneMaps';

export interface ViewSettings {
  exposure: number;
  toneMap: ToneMap;
  paused: boolean;
  /** Stop by itself at this many samples per pixel; 0 = never. */
  targetSpp: number;
}

export interface RenderStats {
  spp: number;
  sppPerSecond: number;
  elapsedMs: number;
  width: number;
  height: number;
  state: 'rendering' | 'paused' | 'done' | 'lost';
}

/** Keep input and the UI above 30 fps. */
const FRAME_BUDGET_MS = 1000 / 30;
/** GPU time per frame to aim for when it can be measured. */
const GPU_BUDGET_MS = 14;
const MAX_SAMPLES_PER_FRAME = 512;
/** Paths in one draw call: keeps each draw well under a second (GPU watchdog). */
const PATHS_PER_DRAW = 1_000_000;

export class RenderLoop {
  samplesPerFrame = 1;
  private timer: GpuTimer;
  private lastFrame = 0;
  private renderedLastFrame = false;
  private displayDirty = true;
  private lastCount = 0;
  private elapsedMs = 0;
  private history: { time: number; spp: number }[] = [];
  private frameHandle = 0;

  constructor(
    private readonly tracer: PathTracer,
    private readonly settings: ViewSettings,
    /** Called before rendering each frame (resolution changes, etc.). */
    private readonly beforeFrame: () => void,
    private readonly onStats: (stats: RenderStats) => void,
  ) {
    this.timer = new GpuTimer(tracer.gl);
    tracer.on('contextlost', () => this.timer.reset());
    tracer.on('contextrestored', () => {
      this.timer = new GpuTimer(tracer.gl);
      this.displayDirty = true;
    });
  }

  start(): void {
    this.frameHandle = requestAnimationFrame(this.frame);
  }

  stop(): void {
    cancelAnimationFrame(this.frameHandle);
  }

  /** Redraw the display (exposure or tone map changed) even when no sample is added. */
  invalidateDisplay(): void {
    this.displayDirty = true;
  }

  get done(): boolean {
    return this.settings.targetSpp > 0 && this.tracer.sampleCount >= this.settings.targetSpp;
  }

  private readonly frame = (now: number): void => {
    this.frameHandle = requestAnimationFrame(this.frame);
    const dt = this.lastFrame ? now - this.lastFrame : 0;
    this.lastFrame = now;
    this.beforeFrame();
    const tracer = this.tracer;
    if (tracer.sampleCount < this.lastCount || tracer.sampleCount === 0) this.restartClock();
    const lost = tracer.contextLost;
    const working = !lost && !this.settings.paused && !this.done;
    if (working) {
      this.adapt(dt);
      let samples = this.samplesPerFrame;
      if (this.settings.targetSpp > 0) samples = Math.min(samples, this.settings.targetSpp - tracer.sampleCount);
      const perDraw = Math.max(1, Math.floor(PATHS_PER_DRAW / (tracer.width * tracer.height)));
      this.timer.measure(samples, () => tracer.render(samples, perDraw));
      this.elapsedMs += this.renderedLastFrame ? dt : 0;
      this.displayDirty = true;
    }
    this.renderedLastFrame = working;
    if (this.displayDirty && !lost) {
      tracer.display({ exposure: this.settings.exposure, toneMap: this.settings.toneMap });
      this.displayDirty = false;
    }
    this.lastCount = tracer.sampleCount;
    this.onStats(this.stats(now, lost));
  };

  private adapt(dt: number): void {
    const msPerSample = this.timer.poll();
    let next = this.samplesPerFrame;
    if (msPerSample !== null && msPerSample > 0) {
      next = 0.6 * next + 0.4 * (GPU_BUDGET_MS / msPerSample);
    } else if (!this.timer.available && this.renderedLastFrame && dt > 0) {
      if (dt > FRAME_BUDGET_MS * 1.15) next = next * 0.7;
      else if (dt < 1000 / 50) next = next * 1.25 + 1;
    }
    this.samplesPerFrame = Math.max(1, Math.min(MAX_SAMPLES_PER_FRAME, Math.floor(next)));
  }

  private restartClock(): void {
    this.elapsedMs = 0;
    this.history = [];
    this.renderedLastFrame = false;
  }

  private stats(now: number, lost: boolean): RenderStats {
    const spp = this.tracer.sampleCount;
    this.history.push({ time: now, spp });
    while (this.history.length > 2 && now - this.history[0].time > 1500) this.history.shift();
    const first = this.history[0];
    const span = now - first.time;
    const sppPerSecond = span > 0 && this.renderedLastFrame ? ((spp - first.spp) * 1000) / span : 0;
    const state = lost ? 'lost' : this.done ? 'done' : this.settings.paused ? 'paused' : 'rendering';
    return { spp, sppPerSecond, elapsedMs: this.elapsedMs, width: this.tracer.width, height: this.tracer.height, state };
  }
}

/** GPU time of the render calls, read back a few frames later without stalling. */
class GpuTimer {
  private readonly ext: { TIME_ELAPSED_EXT: number; GPU_DISJOINT_EXT: number } | null;
  private pending: { query: WebGLQuery; samples: number }[] = [];

  constructor(private readonly gl: WebGL2RenderingContext) {
    this.ext = gl.getExtension('EXT_disjoint_timer_query_webgl2');
  }

  get available(): boolean {
    return this.ext !== null;
  }

  measure(samples: number, work: () => void): void {
    const gl = this.gl;
    const query = this.ext && this.pending.length < 4 ? gl.createQuery() : null;
    if (!query || !this.ext) {
      work();
      return;
    }
    gl.beginQuery(this.ext.TIME_ELAPSED_EXT, query);
    work();
    gl.endQuery(this.ext.TIME_ELAPSED_EXT);
    this.pending.push({ query, samples });
  }

  /** Milliseconds per sample per pixel of the oldest finished measurement, or null. */
  poll(): number | null {
    const gl = this.gl;
    const oldest = this.pending[0];
    if (!this.ext || !oldest || !gl.getQueryParameter(oldest.query, gl.QUERY_RESULT_AVAILABLE)) return null;
    this.pending.shift();
    const disjoint = gl.getParameter(this.ext.GPU_DISJOINT_EXT) as boolean;
    const nanoseconds = gl.getQueryParameter(oldest.query, gl.QUERY_RESULT) as number;
    gl.deleteQuery(oldest.query);
    return disjoint ? null : nanoseconds / 1e6 / oldest.samples;
  }

  reset(): void {
    this.pending = [];
  }
}
