/**
 * The public renderer: a progressive path tracer on a WebGL2 canvas.
 *
 *   const tracer = new PathTracer(canvas, parseScene(json));
 *   function frame() { tracer.render(1); tracer.display(); requestAnimationFrame(frame); }
 *
 * Where one sample over the image is too long for a frame (a slow GPU, a
 * dense mesh), renderPaths(n) advances by about n paths instead: a part of
 * a sample, drawn in tiles (render/tiles.ts), that counts once the whole
 * image has it. Whatever the split, the image has the same bits.
 *
 * Scene edits (`setScene`) re-upload data and restart accumulation; they never
 * recompile shaders. A lost WebGL context is restored by itself: resources are
 * rebuilt and accumulation starts again.
 */
import { NO_ASSETS, type SceneAssets } from '../scene/assets';
import type { Scene } from '../scene/types';
import { type AnyCanvas, createContext, rendererInfo, requireFloatTargets } from './gl/context';
import { flipRows } from './gl/rows';
import { FloatTarget, PingPong } from './gl/targets';
import { AovPass } from './passes/aov';
import { DisplayPass, type DisplayOptions } from './passes/display';
import { TracePass } from './passes/trace';
import type { PrebuiltBvh } from './geometry/world';
import type { SamplerKind } from './sampling';
import { TileLayout, type TileRun } from './tiles';
import { ADAPTIVE_CELL, ADAPTIVE_START, AdaptiveCells, cellGrid, meanImage } from './adaptive';

export interface PathTracerOptions {
  /** Render resolution; defaults to the scene's image size. */
  width?: number;
  height?: number;
  /** Seed of the random streams: the same seed gives the same image. Default 0. */
  seed?: number;
  /**
   * Random numbers of the first dimensions: 'kronecker' (default; a randomly shifted
   * low-discrepancy sequence: unbiased, converges faster) or 'independent' (white noise everywhere).
   */
  sampler?: SamplerKind;
  /**
   * Russian roulette after a few bounces (unbiased). Default false: on
   * SwiftShader it saves no time and adds variance (see integrator.glsl).
   */
  russianRoulette?: boolean;
  /**
   * Adaptive sampling (render/adaptive.ts): after ADAPTIVE_START (4) samples
   * per pixel, render(n) spends n samples per pixel's worth of paths where
   * the image is noisiest, cell by cell of 8x8 pixels; sampleCount is
   * then the mean per pixel. Less error for the same time where the noise
   * is uneven (a caustic, a bright reflection); the image then depends on
   * how the samples were asked for, not only on the seed. Default false.
   * renderPaths draws whole samples with it; accumulation() is null.
   */
  adaptive?: boolean;
  /** Keep the canvas contents after compositing (needed to screenshot it). Default false. */
  preserveDrawingBuffer?: boolean;
  /** The decoded files the scene names (`loadSceneAssets`); needed when it has a map or meshes. */
  assets?: SceneAssets;
  /**
   * Accumulate the denoiser's guides (albedo, normal; see readAovs) while
   * rendering, up to AOV_SAMPLES samples per pixel. Default false: readAovs
   * then renders them when called.
   */
  aovs?: boolean;
  /**
   * Most paths (pixels x samples per pixel) in one draw call: a sample over
   * more pixels is drawn in tiles. Bounds how long one draw runs (a GPU
   * watchdog resets a context whose draw runs for seconds); the `pathsPerDraw`
   * property changes it later. Default DEFAULT_PATHS_PER_DRAW.
   */
  pathsPerDraw?: number;
}

/** Default PathTracerOptions.pathsPerDraw: 2^20 paths, about 0.2-1 s on SwiftShader for simple scenes. */
export const DEFAULT_PATHS_PER_DRAW = 1 << 20;

/** Most samples per pixel of the guide buffers: they converge fast (no lighting) and OIDN needs no more. */
export const AOV_SAMPLES = 16;

/**
 * The denoiser's guide buffers (Open Image Denoise's auxiliary images),
 * RGBA float32, rows top to bottom, width*height*4 each, as readLinear. rgb:
 * the mean over `samples` samples per pixel; alpha: the fraction of samples
 * rejected as non-finite (0 unless something is wrong).
 */
export interface Aovs {
  /** Linear albedo in [0, 1] of the first non-specular hit (through ideal mirrors and smooth glass); the sky's clamped radiance. */
  albedo: Float32Array;
  /** World-space shading normal of that hit, components in [-1, 1] (shorter where a pixel sees several); 0 for the sky. */
  normal: Float32Array;
  /** Samples per pixel behind them. */
  samples: number;
}

interface Resources {
  trace: TracePass;
  display: DisplayPass;
  sums: PingPong;
  /** The guide buffers; created on first use. */
  aov: AovPass | null;
  /** A linear image shown instead of the running mean (showImage), or null. */
  shown: FloatTarget | null;
  /** The adaptive accumulation's mean, for display (created on first use). */
  mean: FloatTarget | null;
}

/**
 * A sample being drawn in tiles: tiles [0, next) of the layout are in
 * sums.write (sums.read plus the sample), and in the guide buffers' write
 * pair too when `aov` (the pass adds a guide sample as well).
 */
interface Pass {
  next: number;
  aov: boolean;
}

export class PathTracer {
  readonly canvas: AnyCanvas;
  readonly gl: WebGL2RenderingContext;
  private scene: Scene;
  private assets: SceneAssets;
  private seed: number;
  private readonly sampler: SamplerKind;
  private readonly russianRoulette: boolean;
  private readonly adaptive: boolean;
  /** Adaptive sampling's cells once it has started (null: every pixel has `samples`). */
  private cells: AdaptiveCells | null = null;
  private keepAovs: boolean;
  private aovSamples = AOV_SAMPLES;
  private size: { width: number; height: number };
  private samples = 0;
  /** Counts restarts of accumulation (scene, size, seed, reset); not a context loss. */
  private generation = 0;
  private resources: Resources | null = null;
  private tiles: TileLayout;
  /** The sample in progress (renderPaths), or null. */
  private pass: Pass | null = null;
  private maxPathsPerDraw = DEFAULT_PATHS_PER_DRAW;
  private readonly listeners = new Map<string, Set<() => void>>();

  constructor(canvas: AnyCanvas | undefined, scene: Scene, options: PathTracerOptions = {}) {
    this.size = { width: options.width ?? scene.image.width, height: options.height ?? scene.image.height };
    this.canvas = canvas ?? new OffscreenCanvas(this.size.width, this.size.height);
    this.scene = scene;
    this.assets = options.assets ?? NO_ASSETS;
    this.seed = options.seed ?? 0;
    this.sampler = options.sampler ?? 'kronecker';
    this.russianRoulette = options.russianRoulette ?? false;
    this.adaptive = options.adaptive ?? false;
    this.keepAovs = options.aovs ?? false;
    if (options.pathsPerDraw !== undefined) this.pathsPerDraw = options.pathsPerDraw;
    this.gl = createContext(this.canvas, options.preserveDrawingBuffer ?? false);
    this.canvas.addEventListener('webglcontextlost', this.onContextLost as EventListener);
    this.canvas.addEventListener('webglcontextrestored', this.onContextRestored as EventListener);
    this.tiles = this.tileLayout();
    this.resizeCanvas();
    this.resources = this.createResources();
  }

  /** Samples per pixel accumulated since the last reset (complete samples: every pixel has them). */
  get sampleCount(): number {
    return this.samples;
  }

  /**
   * Most paths (pixels x samples per pixel) in one draw call; a sample over
   * more pixels is drawn in tiles (PathTracerOptions.pathsPerDraw).
   */
  get pathsPerDraw(): number {
    return this.maxPathsPerDraw;
  }

  set pathsPerDraw(paths: number) {
    if (!(paths >= 1)) throw new RangeError(`pathsPerDraw must be at least 1 (got ${paths})`);
    this.maxPathsPerDraw = paths;
  }

  /** The fraction of the image that has the sample in progress (renderPaths), in [0, 1); 0 when none is. */
  get sampleProgress(): number {
    return this.pass ? this.pass.next / this.tiles.count : 0;
  }

  get width(): number {
    return this.size.width;
  }

  get height(): number {
    return this.size.height;
  }

  get contextLost(): boolean {
    return this.resources === null;
  }

  /** "vendor / renderer" of the WebGL implementation. */
  get renderer(): string {
    return rendererInfo(this.gl);
  }

  /** The current scene's textures on the GPU: the atlas pages' bytes, and one warning per image stored smaller than its size on this device. */
  get textures(): { bytes: number; warnings: readonly string[] } {
    return this.resources?.trace.textures ?? { bytes: 0, warnings: [] };
  }

  get currentScene(): Scene {
    return this.scene;
  }

  /**
   * Replaces the scene (re-upload only; a scene that uses a feature no
   * earlier scene used compiles its program variant once) and restarts
   * accumulation. `assets` holds the files it names; without it the current
   * ones are kept. `options.bvh`: the meshes' BVH built ahead (in a worker:
   * prebuiltBvh over buildBvhAsync(bvhInputs(scene, assets))), used instead
   * of building it on this thread when it fits the scene's meshes. Throws
   * SceneError, changing nothing, when a file the scene names is not in the
   * assets.
   */
  setScene(scene: Scene, assets: SceneAssets = this.assets, options: { bvh?: PrebuiltBvh } = {}): void {
    this.resources?.trace.setScene(scene, assets, this.size.width, this.size.height, options.bvh);
    this.scene = scene;
    this.assets = assets;
    this.reset();
  }

  get currentAssets(): SceneAssets {
    return this.assets;
  }

  /** Changes the render resolution (and the canvas's drawing buffer) and restarts. */
  setSize(width: number, height: number): void {
    if (width === this.size.width && height === this.size.height) return;
    this.size = { width: Math.max(1, Math.floor(width)), height: Math.max(1, Math.floor(height)) };
    this.tiles = this.tileLayout();
    this.resizeCanvas();
    if (this.resources) {
      this.resources.sums.dispose();
      this.resources.sums = new PingPong(this.gl, this.size.width, this.size.height);
      this.resources.mean?.dispose();
      this.resources.mean = null;
      this.resources.aov?.resize(this.size.width, this.size.height);
      this.resources.trace.setScene(this.scene, this.assets, this.size.width, this.size.height);
    }
    this.reset();
  }

  setSeed(seed: number): void {
    this.seed = seed;
    this.reset();
  }

  /** Discards the accumulated samples. */
  reset(): void {
    this.samples = 0;
    this.cells = null;
    this.pass = null;
    this.generation++;
    this.resources?.sums.clear();
    this.resources?.aov?.clear();
    this.showImage(null);
  }

  /**
   * Whether render() accumulates the guide buffers (PathTracerOptions.aovs),
   * and the most samples per pixel they get (1 to AOV_SAMPLES; fewer cost
   * less, and the guides converge fast).
   */
  setAovs(enabled: boolean, maxSamples = AOV_SAMPLES): void {
    this.keepAovs = enabled;
    this.aovSamples = Math.max(1, Math.min(AOV_SAMPLES, Math.floor(maxSamples)));
  }

  /**
   * Adds `samples` samples per pixel, in draws of at most `samplesPerDraw`
   * each and at most `pathsPerDraw` paths (a sample over more pixels is drawn
   * in tiles). A sample in progress (renderPaths) is finished first and
   * counts as one of them. Returns the new sample count. Does nothing while
   * the context is lost.
   */
  render(samples = 1, samplesPerDraw = samples): number {
    const r = this.resources;
    if (!r || this.gl.isContextLost()) return this.samples;
    if (this.adaptive && this.tiles.usable) this.renderAdaptive(r, Math.max(0, Math.floor(samples)), samplesPerDraw);
    else this.renderUniform(r, samples, samplesPerDraw);
    return this.samples;
  }

  private renderUniform(r: Resources, samples: number, samplesPerDraw: number): void {
    let left = samples;
    if (left > 0 && this.pass) {
      this.drawTiles(r, Infinity);
      left -= 1;
    }
    const perDraw = Math.max(1, Math.floor(samplesPerDraw));
    while (left > 0) {
      const n = Math.min(perDraw, left, this.samplesPerFullDraw());
      if (n >= 1) {
        this.drawSamples(r, n);
        left -= n;
      } else {
        this.startPass(r);
        this.drawTiles(r, Infinity);
        left -= 1;
      }
    }
  }

  /**
   * Adaptive sampling: uniform samples up to ADAPTIVE_START (then the noise
   * snapshot), then rounds of `samples` x pixels paths shared
   * by the cells' noise (render/adaptive.ts), in draws of at most
   * pathsPerDraw paths.
   */
  private renderAdaptive(r: Resources, samples: number, samplesPerDraw: number): void {
    let left = samples;
    // The sums as read back for the snapshot, when this call takes it: plan() reads the same.
    let sums: Float32Array | null = null;
    if (!this.cells) {
      const n = Math.min(left, ADAPTIVE_START - this.samples);
      this.renderUniform(r, n, samplesPerDraw);
      left -= n;
      if (this.samples < ADAPTIVE_START) return;
      const layout = this.tiles;
      this.cells = new AdaptiveCells(cellGrid(layout.width, layout.height, Math.min(ADAPTIVE_CELL, layout.size)), this.samples);
      sums = r.sums.read.read();
      this.cells.takeSnapshot(sums);
    }
    if (left <= 0) return;
    const { width, height } = this.size;
    const cells = this.cells;
    const plan = cells.plan(sums ?? r.sums.read.read(), left * width * height);
    const remaining = plan.slice();
    const cellPixels = cells.grid.size * cells.grid.size;
    for (;;) {
      const active = remaining.reduce((n, k) => n + (k > 0 ? 1 : 0), 0);
      if (active === 0) break;
      const cap = Math.max(1, Math.floor(this.pathsPerDraw / (active * cellPixels)));
      const draw = remaining.map((k) => Math.min(k, cap));
      r.sums.copyReadToWrite();
      r.trace.drawCells(r.sums, cells.grid, cells.counts, draw, this.seed);
      r.sums.swap();
      cells.add(draw);
      draw.forEach((k, c) => (remaining[c] -= k));
    }
    this.samples = Math.floor(cells.paths / (width * height));
  }

  /**
   * Traces about `paths` paths (at least one tile of 16x16 pixels): whole
   * samples while `paths` covers the image, else a part of the sample in
   * progress, which counts (sampleCount, display, readLinear) once every
   * pixel has it (sampleProgress tells how far it is). For a frame budget on
   * a slow GPU: the image has the same bits however the paths are split.
   * Returns the paths traced. Does nothing while the context is lost.
   */
  renderPaths(paths: number): number {
    const r = this.resources;
    if (!r || this.gl.isContextLost() || !(paths > 0)) return 0;
    const pixels = this.size.width * this.size.height;
    if (this.adaptive && this.tiles.usable) {
      const n = Math.max(1, Math.round(paths / pixels));
      this.render(n);
      return n * pixels;
    }
    const perTile = this.tiles.pixelsPerTile;
    let left = paths;
    let traced = 0;
    for (;;) {
      if (this.pass) {
        const wanted = Math.max(traced === 0 ? 1 : 0, Math.round(left / perTile));
        const tiles = this.drawTiles(r, wanted);
        if (tiles === 0) break;
        traced += tiles * perTile;
        left -= tiles * perTile;
        continue;
      }
      // Without tiles (points too small for them: TileLayout.usable), the nearest whole number of samples, at least one.
      const whole = this.tiles.usable ? Math.floor(left / pixels) : Math.max(traced === 0 ? 1 : 0, Math.round(left / pixels));
      const n = Math.min(whole, this.samplesPerFullDraw());
      if (n >= 1) {
        this.drawSamples(r, n);
        traced += n * pixels;
        left -= n * pixels;
        continue;
      }
      if (traced > 0 && (left < perTile / 2 || !this.tiles.usable)) break;
      this.startPass(r);
    }
    return traced;
  }

  /** Whole samples per pixel that fit in one draw (pathsPerDraw); 0 when one sample does not (1 without tiles). */
  private samplesPerFullDraw(): number {
    const n = Math.floor(this.pathsPerDraw / (this.size.width * this.size.height));
    return this.tiles.usable ? n : Math.max(1, n);
  }

  /** One draw of `n` whole samples per pixel. */
  private drawSamples(r: Resources, n: number): void {
    r.trace.draw(r.sums, this.samples, n, this.seed);
    r.sums.swap();
    this.samples += n;
    if (this.keepAovs) this.completeAovs(r);
  }

  /** Starts a sample drawn in tiles; with a guide sample too while the guides want one (keepAovs). */
  private startPass(r: Resources): void {
    let aov = false;
    if (this.keepAovs) {
      r.aov ??= new AovPass(this.gl, this.size.width, this.size.height, this.sampler);
      aov = r.aov.samples < Math.min(this.aovSamples, this.samples + 1);
    }
    this.pass = { next: 0, aov };
  }

  /**
   * Draws up to `most` more tiles of the sample in progress, in draws of at
   * most pathsPerDraw paths; when they complete it, swaps the sums and counts
   * the sample. Returns the tiles drawn.
   */
  private drawTiles(r: Resources, most: number): number {
    const pass = this.pass!;
    const end = Math.min(this.tiles.count, pass.next + Math.max(0, most));
    const start = pass.next;
    for (const run of this.tileRuns(start, end)) {
      r.trace.draw(r.sums, this.samples, 1, this.seed, run);
      if (pass.aov) r.aov!.draw(r.trace, 1, this.seed, run);
    }
    pass.next = end;
    if (pass.next === this.tiles.count) {
      r.sums.swap();
      this.samples += 1;
      if (pass.aov) r.aov!.commit(1);
      this.pass = null;
    }
    return end - start;
  }

  /** Tiles [first, end) of the layout in runs of at most pathsPerDraw paths: one draw each. */
  private tileRuns(first: number, end: number): TileRun[] {
    const layout = this.tiles;
    const perDraw = Math.max(1, Math.floor(this.pathsPerDraw / layout.pixelsPerTile));
    const runs: TileRun[] = [];
    for (let next = first; next < end; next += perDraw) runs.push({ layout, first: next, count: Math.min(perDraw, end - next) });
    return runs;
  }

  /**
   * The denoiser's guides (see Aovs) for the current accumulation, over
   * min(AOV_SAMPLES or setAovs's maxSamples, sampleCount) samples per pixel
   * (at least 1): the samples missing are rendered now, so the guides are
   * there whether or not render() kept them.
   */
  readAovs(): Aovs {
    const r = this.requireResources();
    const aov = this.completeAovs(r);
    const sums = aov.readSums();
    const { width, height } = this.size;
    const mean = (data: Float32Array) => flipRows(data.map((v) => v / aov.samples), width, height, 4);
    return { albedo: mean(sums.albedo), normal: mean(sums.normal), samples: aov.samples };
  }

  /**
   * Brings the guides to min(their most samples, sampleCount) samples per pixel (at
   * least 1), in draws of at most pathsPerDraw paths (tiles when one sample
   * is more). A guide sample that a sample in progress was adding tile by
   * tile is dropped: these draws overwrite its tiles.
   */
  private completeAovs(r: Resources): AovPass {
    const aov = (r.aov ??= new AovPass(this.gl, this.size.width, this.size.height, this.sampler));
    if (this.pass) this.pass.aov = false;
    let missing = Math.min(this.aovSamples, Math.max(1, this.samples)) - aov.samples;
    while (missing > 0) {
      const n = Math.min(missing, this.samplesPerFullDraw());
      if (n >= 1) {
        aov.draw(r.trace, n, this.seed);
        missing -= n;
        continue;
      }
      for (const run of this.tileRuns(0, this.tiles.count)) aov.draw(r.trace, 1, this.seed, run);
      aov.commit(1);
      missing -= 1;
    }
    return aov;
  }

  /**
   * Draws the current mean image to the canvas: of the complete samples
   * only (never a mix of n and n + 1 samples). Before the first sample is
   * complete, the part of it drawn so far (renderPaths), black elsewhere.
   * An image given to showImage is shown instead.
   */
  display(options: DisplayOptions = {}): void {
    const r = this.resources;
    if (!r || this.gl.isContextLost()) return;
    const shown = this.shown(r);
    r.display.draw(shown.sums, shown.samples, options, null, this.gl.drawingBufferWidth, this.gl.drawingBufferHeight);
  }

  /** What display() shows: showImage's image (as a mean of 1 sample), the complete samples, or the first sample's tiles so far. */
  private shown(r: Resources): { sums: FloatTarget; samples: number } {
    if (r.shown) return { sums: r.shown, samples: 1 };
    if (this.cells) return { sums: this.adaptiveMean(r), samples: 1 };
    // Both targets are cleared at a reset, so the tiles not yet drawn are black.
    if (this.samples === 0 && this.pass) return { sums: r.sums.write, samples: 1 };
    return { sums: r.sums.read, samples: this.samples };
  }

  /**
   * Shows `linear` (RGBA float32 of the render size, rows top to bottom: a
   * denoised image) instead of the running mean, in display() and
   * readDisplayed(), through the same exposure and tone map; until
   * showImage(null), a restart of accumulation (scene, size, seed, reset) or
   * a lost context. Rendering still adds samples to the mean meanwhile.
   */
  showImage(linear: Float32Array | null): void {
    const r = this.resources;
    r?.shown?.dispose();
    if (r) r.shown = null;
    if (!linear || !r || this.gl.isContextLost()) return;
    const { width, height } = this.size;
    if (linear.length !== width * height * 4) throw new Error(`showImage: expected ${width * height * 4} values (RGBA ${width}x${height}), got ${linear.length}`);
    const gl = this.gl;
    r.shown = new FloatTarget(gl, width, height);
    gl.bindTexture(gl.TEXTURE_2D, r.shown.texture);
    gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, width, height, gl.RGBA, gl.FLOAT, flipRows(linear, width, height, 4));
    gl.bindTexture(gl.TEXTURE_2D, null);
  }

  /** The adaptive accumulation's mean (per-cell counts), in a target display() can read as one sample. */
  private adaptiveMean(r: Resources): FloatTarget {
    const cells = this.cells!;
    const { width, height } = this.size;
    r.mean ??= new FloatTarget(this.gl, width, height);
    const gl = this.gl;
    gl.bindTexture(gl.TEXTURE_2D, r.mean.texture);
    gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, width, height, gl.RGBA, gl.FLOAT, meanImage(cells.grid, r.sums.read.read(), cells.counts));
    gl.bindTexture(gl.TEXTURE_2D, null);
    return r.mean;
  }

  /** Whether display() shows an image given to showImage rather than the running mean. */
  get showsImage(): boolean {
    return !!this.resources?.shown;
  }

  /**
   * The mean linear radiance, RGBA float32, rows from top to bottom. Alpha is
   * the fraction of samples rejected as non-finite (0 unless something is wrong).
   */
  readLinear(): Float32Array {
    const r = this.requireResources();
    const sums = r.sums.read.read();
    if (this.cells) return flipRows(meanImage(this.cells.grid, sums, this.cells.counts), this.size.width, this.size.height, 4);
    const scale = this.samples > 0 ? 1 / this.samples : 0;
    return flipRows(sums.map((v) => v * scale), this.size.width, this.size.height, 4);
  }

  /** The displayed image (exposure, tone map, sRGB; as display() shows it: the mean, or showImage's) as RGBA8, rows from top to bottom. */
  readDisplayed(options: DisplayOptions = {}): Uint8Array {
    const r = this.requireResources();
    const shown = this.shown(r);
    return r.display.read(shown.sums, shown.samples, options, this.size.width, this.size.height);
  }

  /** Blocks until the GPU has finished every queued draw (for timing). */
  finish(): void {
    const pixel = new Float32Array(4);
    const r = this.resources;
    if (!r) return;
    this.gl.bindFramebuffer(this.gl.FRAMEBUFFER, r.sums.read.framebuffer);
    this.gl.readPixels(0, 0, 1, 1, this.gl.RGBA, this.gl.FLOAT, pixel);
    this.gl.bindFramebuffer(this.gl.FRAMEBUFFER, null);
  }

  /**
   * The running sums as they are now, for snapshots (render/snapshot.ts):
   * null while the context is lost. `generation` changes whenever
   * accumulation restarts (scene, size, seed), but not when the context is
   * lost, so a snapshot can be put back after a restore.
   */
  accumulation(): { framebuffer: WebGLFramebuffer; width: number; height: number; samples: number; generation: number } | null {
    const r = this.resources;
    if (!r || this.gl.isContextLost() || this.cells) return null;
    return { framebuffer: r.sums.read.framebuffer, ...this.size, samples: this.samples, generation: this.generation };
  }

  /**
   * Puts back running sums read earlier by `accumulation()` (RGBA32F, rows
   * bottom to top, `samples` samples per pixel) if they belong to the current
   * accumulation (same generation and size). Returns whether it did.
   */
  restoreAccumulation(sums: Float32Array, samples: number, generation: number, width: number, height: number): boolean {
    const r = this.resources;
    if (!r || this.gl.isContextLost() || generation !== this.generation || this.cells) return false;
    if (width !== this.size.width || height !== this.size.height || sums.length !== width * height * 4) return false;
    const gl = this.gl;
    gl.bindTexture(gl.TEXTURE_2D, r.sums.read.texture);
    gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, width, height, gl.RGBA, gl.FLOAT, sums);
    gl.bindTexture(gl.TEXTURE_2D, null);
    this.samples = samples;
    this.pass = null; // its tiles were added to the sums replaced
    return true;
  }

  /** 'contextlost' and 'contextrestored' notifications. */
  on(event: 'contextlost' | 'contextrestored', listener: () => void): () => void {
    if (!this.listeners.has(event)) this.listeners.set(event, new Set());
    this.listeners.get(event)!.add(listener);
    return () => this.listeners.get(event)?.delete(listener);
  }

  dispose(): void {
    this.canvas.removeEventListener('webglcontextlost', this.onContextLost as EventListener);
    this.canvas.removeEventListener('webglcontextrestored', this.onContextRestored as EventListener);
    this.disposeResources();
  }

  private createResources(): Resources {
    const trace = new TracePass(this.gl, this.sampler, this.russianRoulette);
    const display = new DisplayPass(this.gl);
    const sums = new PingPong(this.gl, this.size.width, this.size.height);
    trace.setScene(this.scene, this.assets, this.size.width, this.size.height);
    // An empty vertex array: the full-screen triangle comes from gl_VertexID.
    this.gl.bindVertexArray(this.gl.createVertexArray());
    const aov = this.keepAovs ? new AovPass(this.gl, this.size.width, this.size.height, this.sampler) : null;
    return { trace, display, sums, aov, shown: null, mean: null };
  }

  private disposeResources(): void {
    const r = this.resources;
    this.resources = null;
    if (!r) return;
    r.trace.dispose();
    r.display.dispose();
    r.sums.dispose();
    r.aov?.dispose();
    r.shown?.dispose();
    r.mean?.dispose();
  }

  private requireResources(): Resources {
    if (!this.resources) throw new Error('the WebGL context is lost; wait for it to be restored');
    return this.resources;
  }

  private tileLayout(): TileLayout {
    const range = this.gl.getParameter(this.gl.ALIASED_POINT_SIZE_RANGE) as Float32Array | null;
    return new TileLayout(this.size.width, this.size.height, range?.[1] ?? 1024);
  }

  private resizeCanvas(): void {
    if (this.canvas.width !== this.size.width) this.canvas.width = this.size.width;
    if (this.canvas.height !== this.size.height) this.canvas.height = this.size.height;
  }

  private emit(event: string): void {
    this.listeners.get(event)?.forEach((listener) => listener());
  }

  private readonly onContextLost = (event: Event): void => {
    event.preventDefault(); // allow the browser to restore it
    this.resources = null;  // the handles died with the context
    this.samples = 0;
    this.cells = null;
    this.pass = null;
    this.emit('contextlost');
  };

  private readonly onContextRestored = (): void => {
    requireFloatTargets(this.gl);
    this.resources = this.createResources();
    this.samples = 0;
    this.cells = null;
    this.pass = null;
    this.emit('contextrestored');
  };
}
