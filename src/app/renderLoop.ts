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
import { GpuQueue, GpuTimer, pathsWithRoom, webglFences } from './gpuWork';
import { PathBudget, type PathBudgetOptions } from './pathBudget';

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
 * Most work in flight (submitted, not seen done by its fence), in frames of
 * the budget's target: one running and one waiting keep a GPU that runs
 * behind busy (a fence is seen 2-15 ms after its work on SwiftShader), and
 * what waits for the GPU (a compositor frame, a read-back) waits for at most
 * that. Measured on a 1M-triangle mesh at 512x384 (bench/mesh-page-frames.ts):
 * one frame kept no frame over 100 ms but cost half the samples per second;
 * two, none over 100 ms (max 50-67 ms) at the rate of an unbounded queue
 * (the seed scene: 0.9-0.96x of it; three frames gave the seed scene its
 * rate back but the mesh frames of 83-183 ms; frame-pacing-2026-12-06.md).
 */
const FRAMES_IN_FLIGHT = 2;
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
  private readonly queue: GpuQueue;
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

  constructor(
    private readonly tracer: PathTracer,
    private readonly settings: ViewSettings,
    /** Called before rendering each frame (resolution changes, etc.). */
    private readonly beforeFrame: () => void,
    private readonly onStats: (stats: RenderStats) => void,
  ) {
    this.timer = new GpuTimer(tracer.gl);
    this.queue = new GpuQueue(webglFences(tracer.gl));
    this.budget = new PathBudget(this.budgetOptions());
    tracer.pathsPerDraw = PATHS_PER_DRAW;
    tracer.on('contextlost', () => {
      this.timer.reset();
      this.queue.reset(true);
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
    if (working) {
      this.adapt(dt);
      const target = this.budgetOptions().targetMs;
      const cost = this.budget.costPerPath;
      // The budget's paths, as far as the work still in flight leaves room.
      let paths = pathsWithRoom({
        budgetPaths: this.budget.paths,
        costPerPath: cost,
        pendingMs: this.queue.poll(),
        limitMs: FRAMES_IN_FLIGHT * target,
        frameMs: target,
        leastPaths: 4 * MIN_PATHS,
      });
      if (this.settings.targetSpp > 0) paths = Math.min(paths, (this.settings.targetSpp - count) * tracer.width * tracer.height);
      const before = tracer.sampleCount;
      this.lastPaths = paths > 0 ? this.timer.measure(() => tracer.renderPaths(paths)) : 0;
      // Before the cost is known, a frame counts as the target.
      if (this.lastPaths > 0) this.queue.submitted(cost === null ? target : this.lastPaths * cost);
      this.elapsedMs += this.renderedLastFrame ? dt : 0;
      if (tracer.sampleCount !== before || this.previewDue(now)) this.displayDirty = true;
    }
    this.renderedLastFrame = working;
    if (this.displayDirty && !lost) {
      tracer.display({ exposure: this.settings.exposure, toneMap: this.settings.toneMap });
      this.displayDirty = false;
      this.lastDisplay = now;
    }
    this.lastCount = tracer.sampleCount + tracer.sampleProgress;
    this.onStats(this.stats(now, lost));
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
    const targetMs = this.timer.available ? GPU_BUDGET_MS : FRAME_GAP_BUDGET_MS;
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
