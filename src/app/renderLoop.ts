/**
 * The progressive render loop: every animation frame traces paths, as many
 * as fit a time budget, and shows the running mean. The paths per frame
 * adapt (pathBudget.ts) to the cost per path measured by GPU timer queries
 * (EXT_disjoint_timer_query_webgl2) when the browser has them, else by the
 * frame-to-frame time, so input and the UI stay responsive: a fast GPU gets
 * many samples per frame, a slow one (or a dense mesh) a part of a sample,
 * drawn in tiles (PathTracer.renderPaths) that count once the whole image
 * has the sample.
 */
import type { PathTracer } from '../render/PathTracer';
import type { ToneMap } from '../render/toneMaps';
import type { Material, Scene } from '../scene/types';
import { GpuFences, GpuQueue, GpuTimer } from './gpuWork';

const PARAMS = ((globalThis as unknown as { __loopParams?: { mode?: string; inflight?: number; target?: number; flush?: boolean; statsMs?: number } }).__loopParams ?? {});
import { PathBudget, type PathBudgetOptions } from './pathBudget';
import { LoopTrace } from './loopTrace';

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
  /** The fraction of the image that has the sample in progress (PathTracer.sampleProgress). */
  sampleProgress: number;
  /** Paths the loop traces per frame now (a sample is width x height paths). */
  pathsPerFrame: number;
}

/** GPU time per frame to aim at when it can be measured. */
const GPU_BUDGET_MS = 35;
/**
 * Frame gap to aim at when GPU time cannot be measured: it also holds the
 * display and the page's own work, which the loop cannot tell apart.
 */
const FRAME_GAP_BUDGET_MS = 40;
const MAX_SAMPLES_PER_FRAME = 512;
/** Paths in one draw call: keeps each draw well under a second (GPU watchdog). */
const PATHS_PER_DRAW = 1_000_000;
/**
 * Paths per frame after a change that may change the cost per path a lot,
 * until it is measured: with meshes, 4 tiles of 16x16 (~25 ms at 25 us per
 * path, a 1M-triangle mesh on SwiftShader); without, the cost per path is
 * bounded (a few spheres, no BVH: 0.5-2 us on SwiftShader), so 64 tiles.
 */
const START_PATHS_MESHES = 1024;
const START_PATHS = 16_384;
/** How often the first sample is shown while it fills in. */
const PREVIEW_MS = 250;
/** Fewest paths per frame: one tile (render/tiles.ts). */
const MIN_PATHS = 256;

/**
 * What the cost per path depends on most, beyond the camera: meshes and
 * where they are, objects, material kinds, the environment, bounces. The
 * budget starts small again when it changes.
 */
function costKey(scene: Scene): string {
  const kind = (m: Material | null) => (m ? `${m.type}${m.emission ? '+emission' : ''}` : 'file');
  const environment = scene.environment && 'map' in scene.environment ? scene.environment.map : scene.environment !== null;
  return JSON.stringify([
    scene.meshes.map((m) => [m.file, m.position, m.rotation, m.scale, kind(m.material)]),
    scene.spheres.map((s) => kind(s.material)),
    scene.lights.length,
    scene.ground && kind(scene.ground.material),
    environment,
    scene.render.maxBounces,
  ]);
}

export class RenderLoop {
  private timer: GpuTimer;
  private readonly queue = new GpuQueue();
  private readonly fences: GpuFences;
  private readonly budget: PathBudget;
  private lastFrame = 0;
  private renderedLastFrame = false;
  /** Paths traced in the last frame that rendered. */
  private lastPaths = 0;
  private displayDirty = true;
  private lastDisplay = 0;
  /** Samples (complete plus the fraction in progress) at the end of the last frame. */
  private lastCount = 0;
  private elapsedMs = 0;
  private history: { time: number; spp: number }[] = [];
  private frameHandle = 0;
  private costScene: Scene | null = null;
  private costKey = '';
  private trace: LoopTrace;
  private lastStats = 0;

  constructor(
    private readonly tracer: PathTracer,
    private readonly settings: ViewSettings,
    /** Called before rendering each frame (resolution changes, etc.). */
    private readonly beforeFrame: () => void,
    private readonly onStats: (stats: RenderStats) => void,
  ) {
    this.timer = new GpuTimer(tracer.gl);
    this.trace = new LoopTrace(tracer.gl);
    this.fences = new GpuFences(tracer.gl);
    this.budget = new PathBudget(this.budgetOptions());
    tracer.pathsPerDraw = PATHS_PER_DRAW;
    tracer.on('contextlost', () => {
      this.timer.reset();
      this.queue.reset();
    });
    tracer.on('contextrestored', () => {
      this.timer = new GpuTimer(tracer.gl);
      this.budget.restart();
      this.displayDirty = true;
    });
  }

  /** Paths traced per frame now (for statistics and tests). */
  get pathsPerFrame(): number {
    return this.budget.paths;
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
    const count = tracer.sampleCount + tracer.sampleProgress;
    if (count < this.lastCount || count === 0) this.restartClock();
    const lost = tracer.contextLost;
    const working = !lost && !this.settings.paused && !this.done;
    const row = this.trace.on ? this.trace.begin(now, { dt }) : null;
    const stampBegin = row ? this.trace.stamp() : null;
    if (working) {
      this.adapt(dt);
      let paths = this.budget.paths;
      if (this.settings.targetSpp > 0) paths = Math.min(paths, (this.settings.targetSpp - count) * tracer.width * tracer.height);
      // While the GPU is predicted to be behind by a frame's work, this frame adds nothing.
      const target = this.budgetOptions().targetMs;
      if (row) {
        row.backlog = this.queue.backlog(now);
        row.cost = this.budget.costPerPath ?? -1;
        row.budget = paths;
      }
      if (PARAMS.mode === 'fence') {
        this.fences.poll();
        if (row) row.pendingMs = this.fences.pendingMs;
        if (this.fences.pending > 0 && this.fences.pendingMs > ((PARAMS.inflight ?? 1) - 1) * target) paths = 0;
      } else if (PARAMS.mode === 'fill') {
        this.fences.poll();
        if (row) row.pendingMs = this.fences.pendingMs;
        const room = (PARAMS.inflight ?? 2) * target - this.fences.pendingMs;
        const cost = this.budget.costPerPath;
        if (cost !== null) paths = Math.min(paths, Math.floor(room / cost));
        if (paths < Math.min(this.budget.paths, MIN_PATHS * 4)) paths = 0;
      } else if (this.queue.backlog(now) > target) paths = 0;
      const before = tracer.sampleCount;
      this.lastPaths = paths > 0 ? this.timer.measure(() => tracer.renderPaths(paths)) : 0;
      if (PARAMS.flush && this.lastPaths > 0) tracer.gl.flush();
      this.queue.submitted(now, this.lastPaths * (this.budget.costPerPath ?? target / Math.max(1, this.lastPaths)));
      if ((PARAMS.mode === 'fence' || PARAMS.mode === 'fill') && this.lastPaths > 0) this.fences.submitted(this.lastPaths * (this.budget.costPerPath ?? target / Math.max(1, this.lastPaths)));
      this.elapsedMs += this.renderedLastFrame ? dt : 0;
      if (tracer.sampleCount !== before || this.previewDue(now)) this.displayDirty = true;
    }
    this.renderedLastFrame = working;
    if (this.displayDirty && !lost) {
      tracer.display({ exposure: this.settings.exposure, toneMap: this.settings.toneMap });
      this.displayDirty = false;
      this.lastDisplay = now;
      if (row) row.display = 1;
    }
    if (row) {
      row.paths = this.lastPaths;
      this.trace.end(row, stampBegin, this.trace.stamp());
    }
    this.lastCount = tracer.sampleCount + tracer.sampleProgress;
    const st = this.stats(now, lost);
    if (!PARAMS.statsMs || now - this.lastStats >= PARAMS.statsMs || st.state !== 'rendering') {
      this.lastStats = now;
      this.onStats(st);
    }
  };

  /**
   * Whether to show the first sample as it fills in: every PREVIEW_MS, while
   * it has more than PREVIEW_MS * 4 of work left (a display costs a frame's
   * worth of work with a software GPU, the page's compositing included, and
   * a first sample due soon is better shown whole).
   */
  private previewDue(now: number): boolean {
    const tracer = this.tracer;
    if (tracer.sampleCount > 0 || this.lastPaths === 0 || now - this.lastDisplay < PREVIEW_MS) return false;
    const msPerPath = this.budget.costPerPath;
    if (msPerPath === null) return true;
    return (1 - tracer.sampleProgress) * tracer.width * tracer.height * msPerPath > PREVIEW_MS * 4;
  }

  private budgetOptions(): PathBudgetOptions {
    const pixels = this.tracer.width * this.tracer.height;
    const targetMs = PARAMS.target ?? (this.timer.available ? GPU_BUDGET_MS : FRAME_GAP_BUDGET_MS);
    const startPaths = this.tracer.currentScene.meshes.length ? START_PATHS_MESHES : START_PATHS;
    return { targetMs, startPaths, minPaths: MIN_PATHS, maxPaths: MAX_SAMPLES_PER_FRAME * pixels };
  }

  private adapt(dt: number): void {
    const scene = this.tracer.currentScene;
    this.budget.setOptions(this.budgetOptions());
    let changed = false;
    if (scene !== this.costScene) {
      this.costScene = scene;
      const key = costKey(scene);
      changed = key !== this.costKey;
      if (changed && this.costKey) this.budget.restart();
      this.costKey = key;
    }
    if (changed) {
      this.timer.discard(); // measurements of the old scene
      return;
    }
    if (this.timer.available) {
      for (const m of this.timer.poll()) this.budget.observe(m.ms, m.paths);
    } else if (this.renderedLastFrame && dt > 0) {
      this.budget.observe(dt, this.lastPaths);
    }
    if (this.renderedLastFrame && dt > 0) this.budget.observeGap(dt, this.lastPaths);
  }

  private restartClock(): void {
    this.elapsedMs = 0;
    this.history = [];
    this.renderedLastFrame = false;
  }

  private stats(now: number, lost: boolean): RenderStats {
    const spp = this.tracer.sampleCount;
    // The rate counts the sample in progress: a slow one is a steady fraction per frame, not a jump now and then.
    this.history.push({ time: now, spp: spp + this.tracer.sampleProgress });
    while (this.history.length > 2 && now - this.history[0].time > 1500) this.history.shift();
    const first = this.history[0];
    const span = now - first.time;
    const sppPerSecond = span > 0 && this.renderedLastFrame ? ((this.history[this.history.length - 1].spp - first.spp) * 1000) / span : 0;
    const state = lost ? 'lost' : this.done ? 'done' : this.settings.paused ? 'paused' : 'rendering';
    const { width, height } = this.tracer;
    const sampleProgress = this.tracer.sampleProgress;
    return { spp, sppPerSecond, elapsedMs: this.elapsedMs, width, height, state, sampleProgress, pathsPerFrame: this.budget.paths };
  }
}
