/**
 * The page's "Denoise" view. While the view is still, the running mean is
 * denoised (src/denoise: Open Image Denoise's network in a worker) when its
 * sample count first reaches 4, 16, 64, 256... spp, and once more when
 * rendering stops (paused, target reached). A result is shown through the
 * tracer's own display pass (PathTracer.showImage: same exposure and tone
 * map) only if the accumulation it came from is still current; any restart
 * (camera, edit, resize) shows the raw image again at once, because the
 * tracer drops the shown image itself.
 *
 * The main thread never waits for the network: each milestone costs one
 * read-back (colour and guides), then tracing goes on while the worker runs.
 * At most one denoise is in flight; a milestone reached meanwhile starts
 * from the state current when the worker is free again.
 */
import type { Denoiser } from '../denoise/denoiser';
import type { PathTracer } from '../render/PathTracer';

/** The first milestone; each next one has FACTOR times the samples. */
const FIRST_MILESTONE = 4;
const FACTOR = 4;
/**
 * Samples per pixel of the guides (albedo, normal). Measured on the seed
 * scene at 16 spp: denoised relMSE with 8-sample guides is 2% above that
 * with 16, with 4 it is 10% above; each guide sample costs about 40% of a
 * path sample (80 ms at 512x384 here), so 8 saves that much in the first
 * 16 spp for almost nothing.
 */
export const GUIDE_SAMPLES = 8;
/**
 * The largest tile the network sees (DenoiserOptions.maxTileSize). The
 * library's 512 splits the page's usual sizes into overlapping tiles: at
 * 664x498 six tiles took 6.3 s here, one tile of 768 took 3.0 s. 768 keeps
 * most canvases in one piece while bounding the worker's memory (about
 * 75 MB per full-resolution 32-channel activation).
 */
const MAX_TILE_SIZE = 768;

export type ShownImage = 'raw' | 'denoised';

export interface DenoiseState {
  /** What the canvas shows. */
  shown: ShownImage;
  /** One line for the status bar ('' when the toggle is off). */
  text: string;
  /** Samples per pixel behind the shown denoised image, else 0. */
  spp: number;
}

/** The largest milestone (4, 16, 64...) not above `spp`; 0 below the first. */
export function milestoneAtOrBelow(spp: number): number {
  let milestone = 0;
  for (let next = FIRST_MILESTONE; next <= spp; next *= FACTOR) milestone = next;
  return milestone;
}

/** The page's denoiser: OIDN's network in a worker (the page's CSP rightly forbids WebAssembly on the main thread). */
function startDenoiserWorker(): Promise<Denoiser> {
  return import('../denoise/workerClient').then((m) => m.createDenoiserWorker({ maxTileSize: MAX_TILE_SIZE }));
}

/** What the denoiser needs to know of the page. */
export interface DenoiseHooks {
  /** True while the camera or an object moves (no denoise then: it would be stale at once). */
  moving(): boolean;
  /** True when rendering has stopped (paused, target spp reached): the final state is denoised. */
  stopped(): boolean;
  /** The canvas must be drawn again (the shown image changed while no samples are added). */
  redisplay(): void;
}

/** A denoise in flight: what it was read from. */
interface Job {
  session: number;
  generation: number;
  spp: number;
  started: number;
}

export class LiveDenoiser {
  /** Reports what is shown after every change (status bar, tests). */
  onState: (state: DenoiseState) => void = () => {};
  /** The denoiser could not start or failed: the toggle has been turned off. */
  onFailure: (message: string) => void = () => {};

  private denoiser: Promise<Denoiser> | null = null;
  /** Counts start()s: a result of an earlier session (toggle turned off since) is dropped. */
  private session = 0;
  private job: Job | null = null;
  /** The accumulation (PathTracer generation) the requests below belong to. */
  private generation = -1;
  private requestedSpp = 0;
  /** The denoised image on the canvas: its spp, how long it took, its linear RGBA. */
  private result: { spp: number; seconds: number; linear: Float32Array } | null = null;
  private lastText = '\u0000';

  constructor(
    private readonly tracer: PathTracer,
    private readonly view: { denoise: boolean },
    private readonly hooks: DenoiseHooks,
    /** Starts a denoiser (a worker); tests pass their own. */
    private readonly createDenoiser: () => Promise<Denoiser> = startDenoiserWorker,
  ) {
    // The shown image died with the context; denoise again what comes back.
    tracer.on('contextrestored', () => this.forgetRequests());
  }

  /** Call once per frame: follows the toggle, notices restarts, starts a denoise when one is due. */
  tick(): void {
    if (this.view.denoise !== (this.denoiser !== null)) {
      if (this.view.denoise) this.start();
      else this.stop();
    }
    if (!this.denoiser) return;
    const accumulation = this.tracer.accumulation();
    if (!accumulation) return; // context lost
    if (accumulation.generation !== this.generation) {
      // A restart: the tracer already shows the raw image again.
      this.generation = accumulation.generation;
      this.forgetRequests();
      if (this.job) this.abandonJob();
    }
    if (this.result && !this.tracer.showsImage) this.forgetRequests();
    if (!this.job && !this.hooks.moving() && this.due(accumulation.samples)) this.begin(accumulation.generation, accumulation.samples);
    this.report();
  }

  private due(spp: number): boolean {
    if (spp < 1) return false;
    if (milestoneAtOrBelow(spp) > milestoneAtOrBelow(this.requestedSpp)) return true;
    return this.hooks.stopped() && spp > this.requestedSpp;
  }

  private forgetRequests(): void {
    this.requestedSpp = 0;
    this.result = null;
  }

  /** Turns denoising on: guides are kept while rendering, and the worker starts (overlapping the first samples). */
  private start(): void {
    this.tracer.setAovs(true, GUIDE_SAMPLES);
    this.generation = -1;
    this.forgetRequests();
    this.spawn();
  }

  /** A new worker (and session: whatever an earlier one still answers is ignored). */
  private spawn(): void {
    const session = ++this.session;
    this.job = null;
    this.denoiser = this.createDenoiser();
    this.denoiser.catch((error: unknown) => this.fail(session, error));
  }

  /**
   * The denoise in flight belongs to an accumulation that is gone. The
   * network cannot be interrupted, so a fresh worker replaces this one: its
   * start-up (1-2 s here) is shorter than the rest of a denoise (several
   * seconds at the page's size), which the new view would otherwise wait for.
   */
  private abandonJob(): void {
    const old = this.denoiser;
    this.spawn();
    old?.then((d) => d.dispose(), () => {});
  }

  private stop(): void {
    this.session++;
    const denoiser = this.denoiser;
    this.denoiser = null;
    this.job = null;
    this.forgetRequests();
    this.tracer.setAovs(false);
    this.tracer.showImage(null);
    this.hooks.redisplay();
    denoiser?.then((d) => d.dispose(), () => {});
    this.report();
  }

  private fail(session: number, error: unknown): void {
    if (session !== this.session) return;
    this.view.denoise = false;
    this.stop();
    this.onFailure((error as Error)?.message ?? String(error));
  }

  /** Reads the current colour and guides back (the one read-back of a milestone) and hands them to the worker. */
  private begin(generation: number, spp: number): void {
    const denoiser = this.denoiser!;
    const job: Job = { session: this.session, generation, spp, started: performance.now() };
    this.job = job;
    this.requestedSpp = spp;
    const { width, height } = this.tracer;
    const color = this.tracer.readLinear();
    const { albedo, normal } = this.tracer.readAovs();
    denoiser
      .then((d) => d.denoise({ width, height, color, albedo, normal }))
      .then(
        (denoised) => this.finish(job, denoised),
        (error: unknown) => this.fail(job.session, error),
      );
  }

  private finish(job: Job, denoised: Float32Array): void {
    if (job.session !== this.session) return; // turned off (and maybe on) since
    this.job = null;
    // Only the accumulation it was read from may show it: a restart since makes it stale.
    const current = this.tracer.accumulation();
    if (current?.generation !== job.generation) return;
    this.tracer.showImage(denoised);
    this.hooks.redisplay();
    this.result = { spp: job.spp, seconds: (performance.now() - job.started) / 1000, linear: denoised };
    this.report();
  }

  /** The denoised linear image (RGBA, rows top to bottom) while it is the one shown, else null. */
  get shownLinear(): Float32Array | null {
    return this.result && this.tracer.showsImage ? this.result.linear : null;
  }

  private report(): void {
    const state = this.state();
    if (state.text === this.lastText) return;
    this.lastText = state.text;
    this.onState(state);
  }

  private state(): DenoiseState {
    if (!this.denoiser) return { shown: 'raw', text: '', spp: 0 };
    const running = this.job ? `denoising ${this.job.spp} spp…` : '';
    if (this.result && this.tracer.showsImage) {
      const text = `denoised at ${this.result.spp} spp (${this.result.seconds.toFixed(1)} s)`;
      return { shown: 'denoised', text: running ? `${text}; ${running}` : text, spp: this.result.spp };
    }
    return { shown: 'raw', text: running ? `raw; ${running}` : `raw; denoised from ${FIRST_MILESTONE} spp when still`, spp: 0 };
  }
}
