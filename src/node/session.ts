/**
 * Drives the headless renderer page in Debian's Chromium (SwiftShader WebGL2)
 * through playwright-core. Shared by the CLI, the benchmark and the tests, so
 * all of them render through exactly the page's code.
 */
import { existsSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { chromium, type Browser, type Page } from 'playwright-core';
import type { DisplayOptions } from '../render/passes/display';
import { TONEMAPS } from '../render/toneMaps';
import type { SceneAssets } from '../scene/assets';
import type { Scene } from '../scene/types';
import type { HeadlessApi, LoadOptions, LoadResult, OutputRequest } from '../headless/main';
import type { KernelRequest } from '../headless/kernels';
import type { DenoiseRequest } from '../headless/denoise';
import { hasAssets, packAssets } from './assetTransfer';
import { serveDirectory, type StaticServer } from './server';
import { mark } from './timing';

export { TONEMAPS };
export type { LoadOptions };

/** RenderSession.readOutputs's request: the page's OutputRequest, the tone map by name. */
export type OutputsRequest = Omit<OutputRequest, 'display'> & { display: { exposure: number; toneMap: string } };

export const DEFAULT_CHROMIUM = '/usr/bin/chromium';

/** Flags for headless Chromium with CPU WebGL2 (SwiftShader) on a machine without a GPU. */
export const CHROMIUM_ARGS = [
  '--headless=new',
  '--no-sandbox',
  '--use-angle=swiftshader',
  '--enable-unsafe-swiftshader',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--no-first-run',
];

/**
 * Playwright's own signal handlers would close Chromium and exit the process
 * on Ctrl-C before its owner (the CLI) can report and clean up; owners handle
 * signals themselves.
 */
const LAUNCH_OPTIONS = {
  headless: true,
  args: CHROMIUM_ARGS,
  handleSIGINT: false,
  handleSIGTERM: false,
  handleSIGHUP: false,
} as const;

export class ChromiumNotFoundError extends Error {
  constructor(path: string) {
    super(`Chromium not found at ${path}: install it with "apt-get install chromium" or set PATHTRACE_CHROMIUM to its path`);
    this.name = 'ChromiumNotFoundError';
  }
}

export class WebPageNotBuiltError extends Error {
  constructor() {
    super('the web page is not built (dist/web/headless.html is missing): run "npm run build"');
    this.name = 'WebPageNotBuiltError';
  }
}

export interface SessionOptions {
  chromiumPath?: string;
  /** The built page to drive (default: dist/web); benchmarks point it at another build to compare. */
  webRoot?: string;
  /**
   * Gives up opening: once aborted, the next step (after Chromium's launch,
   * the new page, the page load) closes what is open and rejects with the
   * signal's reason. The CLI aborts when a file the scene names is bad.
   */
  signal?: AbortSignal;
}

export interface RenderSession {
  /**
   * Loads a parsed scene into a fresh PathTracer in the page, with the bytes
   * of the files it names (by name as written; see readSceneFiles), which
   * the page decodes, or with them decoded already (`assets`, which the page
   * fetches as raw bytes and does not decode again; what the CLI passes).
   */
  /** The renderer's name; the textures' GPU bytes and warnings (images halved to fit), from pages that report them. */
  load(scene: Scene, options: LoadOptions, files?: Record<string, Uint8Array>, assets?: SceneAssets): Promise<LoadResult>;
  /**
   * Renders `samples` more samples per pixel, split into draws of about
   * DRAW_TARGET_MS (tiles of a sample when one sample is more; the first
   * draws after load are small, until the scene's cost is measured);
   * resolves with the total.
   */
  render(samples: number): Promise<number>;
  /** Discards the accumulated samples; the shaders stay compiled (the benchmark times from here). */
  reset(): Promise<void>;
  /** Mean linear radiance, RGBA float32, rows top to bottom, width*height*4. */
  readLinear(): Promise<Float32Array>;
  /**
   * The denoiser's guides (PathTracer.readAovs): albedo and normal of the
   * first non-specular hit, RGBA float32, rows top to bottom, width*height*4
   * each; rendered now if the tracer did not keep them (LoadOptions.aovs).
   */
  readAovs(): Promise<{ albedo: Float32Array; normal: Float32Array; samples: number }>;
  /** The displayed image exactly as the page shows it: RGBA8 sRGB, rows top to bottom. */
  readDisplayed(options: { exposure: number; toneMap: string }): Promise<Uint8Array>;
  /**
   * The CLI's images in one call, each crossing from the page once: the
   * displayed image, the linear one (request.linear) and the guides
   * (request.aovs); with request.denoise the page denoises the final image
   * with the guides and both images are of the denoised one.
   */
  readOutputs(request: OutputsRequest): Promise<{ displayed: Uint8Array; linear?: Float32Array; albedo?: Float32Array; normal?: Float32Array }>;
  close(): Promise<void>;
  /** The page, for tests that need more than the API above. */
  readonly page: Page;
  probe(): Promise<{ webgl2: boolean; floatTargets: boolean; renderer: string }>;
  runKernel(request: KernelRequest): Promise<Float32Array>;
  /** The compile log of a fragment-shader chunk (after the common chunks), or null if it compiles. */
  compileLog(name: string, source: string): Promise<string | null>;
  /** Denoises linear RGBA arrays (rows top to bottom) in the page with src/denoise. */
  denoise(input: DenoiseArrays, options?: DenoiseRequest['options']): Promise<DenoiseOutcome>;
  /** A linear RGBA image through the page's display pass, as readDisplayed() shows the tracer's. */
  displayLinear(linear: Float32Array, width: number, height: number, options: { exposure: number; toneMap: string }): Promise<Uint8Array>;
}

export interface DenoiseArrays {
  width: number;
  height: number;
  color: Float32Array;
  albedo: Float32Array;
  normal: Float32Array;
}

export interface DenoiseOutcome {
  data: Float32Array;
  milliseconds: number;
  setupMilliseconds: number;
  backend: string;
  longestMainThreadGap: number;
}

/** The built page directory: dist/web next to the bundled CLI, or from the sources. */
export function webRoot(): string {
  const candidates = ['../web/', '../../dist/web/'].map((p) => fileURLToPath(new URL(p, import.meta.url)));
  const found = candidates.find((dir) => existsSync(`${dir}headless.html`));
  if (!found) throw new WebPageNotBuiltError();
  return found;
}

export function chromiumPath(options: SessionOptions = {}): string {
  const path = options.chromiumPath ?? process.env.PATHTRACE_CHROMIUM ?? DEFAULT_CHROMIUM;
  if (!existsSync(path)) throw new ChromiumNotFoundError(path);
  return path;
}

export async function launchChromium(options: SessionOptions = {}): Promise<Browser> {
  return chromium.launch({ executablePath: chromiumPath(options), ...LAUNCH_OPTIONS });
}

/**
 * Draw calls of render() aim at this long: well under a GPU watchdog
 * (seconds), long enough that the cost of a draw itself is negligible. The
 * paths per draw follow from the last render() call's time per path.
 */
const DRAW_TARGET_MS = 250;
/**
 * Paths per draw before a scene's cost is known (after load): about 0.4 s
 * at 25 us per path, a 1M-triangle mesh at 512x384 on SwiftShader.
 */
const FIRST_PATHS_PER_DRAW = 16_384;
/** Bounds of the paths per draw: the most is ~0.4 s on SwiftShader for simple scenes; more per draw amortizes the per-draw cost (and a sample that scatters nowhere costs less: trace.frag). */
const MIN_PATHS_PER_DRAW = 4096;
const MAX_PATHS_PER_DRAW = 1_000_000;

export async function openRenderSession(options: SessionOptions = {}): Promise<RenderSession> {
  const root = options.webRoot ?? webRoot();
  chromiumPath(options); // fail before starting the server when Chromium is missing
  const server: StaticServer = await serveDirectory(root);
  let browser: Browser | undefined;
  const { signal } = options;
  try {
    mark('server up');
    signal?.throwIfAborted();
    browser = await launchChromium(options);
    mark('chromium launched');
    signal?.throwIfAborted();
    const page = await browser.newPage();
    mark('page opened');
    signal?.throwIfAborted();
    const pageErrors: string[] = [];
    page.on('pageerror', (error) => pageErrors.push(error.message));
    await page.goto(`${server.url}headless.html`);
    mark('page loaded');
    signal?.throwIfAborted();
    // The page is ready at its load event (its module has run): one evaluate
    // says so without waitForFunction's polling machinery (Playwright's
    // injected script, compiled in the page first).
    const ready = await page.evaluate(() => document.body.dataset.ready === 'true');
    if (!ready) await page.waitForFunction(() => document.body.dataset.ready === 'true', undefined, { timeout: 30_000 });
    mark('page ready');
    return createSession(page, browser, server, pageErrors);
  } catch (error) {
    await browser?.close();
    await server.close();
    throw error;
  }
}

function createSession(page: Page, browser: Browser, server: StaticServer, pageErrors: string[]): RenderSession {
  let pixels = 1;
  let pathsPerDraw = FIRST_PATHS_PER_DRAW;
  // Calls window.pathtrace[method](...args) in the page (by name: the page's
  // Content-Security-Policy rightly forbids eval).
  const call = async <M extends keyof HeadlessApi>(
    method: M,
    ...args: Parameters<HeadlessApi[M]>
  ): Promise<ReturnType<HeadlessApi[M]>> => {
    try {
      return (await page.evaluate(
        ([m, a]) => (window.pathtrace[m] as (...x: unknown[]) => unknown)(...a),
        [method, args] as [M, unknown[]],
      )) as ReturnType<HeadlessApi[M]>;
    } catch (error) {
      const detail = pageErrors.length ? ` (${pageErrors.join('; ')})` : '';
      const message = (error as Error).message.replace(/^page\.evaluate: /, '');
      const withoutStack = message.split('\n').filter((line) => !/^\s+at /.test(line)).join('\n');
      throw new Error(`${withoutStack}${detail}`);
    }
  };
  return {
    page,
    probe: () => call('probe'),
    async load(scene, options, files = {}, assets) {
      pixels = options.width * options.height;
      pathsPerDraw = FIRST_PATHS_PER_DRAW; // a new scene: its cost is not known yet
      const encoded = Object.fromEntries(Object.entries(files).map(([name, bytes]) => [name, Buffer.from(bytes).toString('base64')]));
      if (!hasAssets(assets)) return call('load', scene, options, encoded);
      const { manifest, bytes } = packAssets(assets);
      manifest.url = server.publish(bytes);
      return call('load', scene, options, encoded, manifest);
    },
    async render(samples) {
      // Whole samples per draw too, for pages built before pathsPerDraw (bench/versus.ts).
      const perDraw = Math.max(1, Math.floor(pathsPerDraw / pixels));
      const { sampleCount, milliseconds } = await call('render', samples, perDraw, pathsPerDraw);
      const msPerPath = milliseconds / (samples * pixels);
      if (samples > 0 && msPerPath > 0) {
        pathsPerDraw = Math.round(Math.min(MAX_PATHS_PER_DRAW, Math.max(MIN_PATHS_PER_DRAW, DRAW_TARGET_MS / msPerPath)));
      }
      return sampleCount;
    },
    async reset() {
      await call('reset');
    },
    async readLinear() {
      return toFloat32(await call('readLinear'));
    },
    async readAovs() {
      const { albedo, normal, samples } = await call('readAovs');
      return { albedo: toFloat32(albedo), normal: toFloat32(normal), samples };
    },
    async readDisplayed(options) {
      const toneMap = options.toneMap as DisplayOptions['toneMap'];
      return new Uint8Array(Buffer.from(await call('readDisplayed', { exposure: options.exposure, toneMap }), 'base64'));
    },
    async readOutputs(request) {
      const toneMap = request.display.toneMap as DisplayOptions['toneMap'];
      const result = await call('readOutputs', { ...request, display: { exposure: request.display.exposure, toneMap } });
      const optional = (base64: string | undefined) => (base64 === undefined ? undefined : toFloat32(base64));
      return {
        displayed: new Uint8Array(Buffer.from(result.displayed, 'base64')),
        linear: optional(result.linear),
        albedo: optional(result.albedo),
        normal: optional(result.normal),
      };
    },
    compileLog: (name, source) => call('compileLog', name, source),
    async runKernel(request) {
      return toFloat32(await call('runKernel', request));
    },
    async denoise(input, options) {
      const base64 = (f: Float32Array) => Buffer.from(f.buffer, f.byteOffset, f.byteLength).toString('base64');
      const { width, height } = input;
      const request = { width, height, color: base64(input.color), albedo: base64(input.albedo), normal: base64(input.normal), options };
      const result = await call('denoise', request);
      return { ...result, data: toFloat32(result.data) };
    },
    async displayLinear(linear, width, height, options) {
      const toneMap = options.toneMap as DisplayOptions['toneMap'];
      const encoded = Buffer.from(linear.buffer, linear.byteOffset, linear.byteLength).toString('base64');
      return new Uint8Array(Buffer.from(await call('displayLinear', encoded, width, height, { exposure: options.exposure, toneMap }), 'base64'));
    },
    async close() {
      await browser.close();
      await server.close();
    },
  };
}

function toFloat32(base64: string): Float32Array {
  const bytes = Buffer.from(base64, 'base64');
  return new Float32Array(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength));
}
