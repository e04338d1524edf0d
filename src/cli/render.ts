/**
 * `pathtrace render`: parse the flags and the scene (a scene file's, or one
 * made around a model file: model.ts), check the output paths,
 * then drive a headless Chromium session: load, render in chunks sized to
 * take about half a second each (so the progress bar moves and no draw runs
 * long), read back the displayed and linear images, and write PNG / PFM
 * atomically.
 */
import { resolve } from 'node:path';
import type { RenderSession, SessionOptions } from '../node/session';
import { meshWarnings, type SceneAssets } from '../scene/assets';
import type { Scene } from '../scene/types';
import { parseRenderArgs, resolveSize, type AovPaths, type Budget, type RawRenderOptions, type RenderArgs } from './args';
import { CliError, EXIT_INTERRUPTED, failure, firstLine, oneLine, usageError } from './errors';
import { checkWritable, defaultPngPath, writeOutputs } from './output';
import { encodePfm } from '../image/pfm';
import { denoiseFinalImage, readGuides, type DenoiseSession, type Guides } from './denoise';
import { encodePng } from './png';
import { createProgress, formatRate, type Progress, type ProgressStream } from './progress';
import { loadSceneFile, loadSceneFiles } from './validate';
import { checkNoModelOptions, isModelFile, loadModelFiles, loadModelScene, modelScenePath } from './model';
import type { SceneFiles } from '../node/sceneFiles';
import { mark } from '../node/timing';

/**
 * The part of a RenderSession the CLI uses: readOutputs when the page has it
 * (every image crosses from the page once), else the separate reads (the
 * denoiser's part only with --denoise).
 */
export type CliSession = Pick<RenderSession, 'load' | 'render' | 'readLinear' | 'readDisplayed' | 'close'> &
  Partial<DenoiseSession> &
  Partial<Pick<RenderSession, 'readOutputs'>>;

/** What render needs from src/node/session.ts; injected in tests. */
export interface SessionModule {
  openRenderSession(options?: SessionOptions): Promise<CliSession>;
  TONEMAPS: readonly string[];
}

/** Session errors whose message is already a complete, actionable sentence. */
const SELF_EXPLAINING_ERRORS = new Set(['ChromiumNotFoundError', 'WebPageNotBuiltError']);

export interface RenderContext {
  session: SessionModule;
  stderr: ProgressStream;
  /** Directory for the default output file; undefined = the current directory. */
  cwd?: string;
  /** Clock in seconds; injectable for tests. */
  now?: () => number;
}

/** Each render() call aims at this long: short enough for a lively bar and no GPU watchdog trouble. */
export const TARGET_CHUNK_SECONDS = 0.5;
/** A chunk grows by at most this factor per call, so one bad rate estimate cannot make a huge draw. */
const MAX_CHUNK_GROWTH = 4;

export interface RenderOutcome {
  spp: number;
  seconds: number;
  width: number;
  height: number;
  files: string[];
}

export async function renderCommand(sceneFile: string, raw: RawRenderOptions, ctx: RenderContext): Promise<RenderOutcome> {
  mark('render command');
  const args = parseRenderArgs(raw, ctx.session.TONEMAPS);
  const { scene, readFiles } = await loadRenderScene(sceneFile, raw, args, ctx.cwd);
  mark('scene parsed');
  const { width, height } = resolveSize(scene.image, args);
  const pngPath = raw.output ?? defaultPngPath(sceneFile, ctx.cwd);
  const hdrPath = raw.hdr;
  // The files the scene names are read and decoded while Chromium starts
  // (its start-up is mostly other processes'). Their problems still come
  // first: before a bad output path's, and before any session error.
  let assetsLoading: Promise<SceneAssets> | undefined;
  const loadAssets = () =>
    (assetsLoading ??= readFiles().then(({ assets }) => {
      mark('scene files read');
      return assets;
    }));
  const assetsFirst = async (error: unknown): Promise<never> => {
    if (!(error instanceof CliError && error.exitCode === EXIT_INTERRUPTED)) await loadAssets();
    throw error;
  };
  await checkOutputs(pngPath, hdrPath, args.aov).catch(assetsFirst);

  const progress = createProgress(ctx.stderr, args.budget, width * height);
  const now = ctx.now ?? (() => performance.now() / 1000);
  try {
    const result = await withSession(
      ctx.session,
      progress,
      async (session) => renderImages(session, scene, await loadAssets(), args, { width, height }, progress, now, hdrPath !== undefined),
      loadAssets,
    ).catch(assetsFirst);
    progress.stop();
    for (const warning of result.warnings ?? []) ctx.stderr.write(`warning: ${warning}\n`);
    const outputs: { path: string; data: Uint8Array }[] = [{ path: pngPath, data: encodePng(width, height, result.displayed) }];
    if (hdrPath !== undefined && result.linear) outputs.push({ path: hdrPath, data: encodePfm(width, height, result.linear) });
    if (args.aov && result.guides) {
      outputs.push({ path: args.aov.albedo, data: encodePfm(width, height, result.guides.albedo) });
      outputs.push({ path: args.aov.normal, data: encodePfm(width, height, result.guides.normal) });
    }
    mark('images read back and encoded');
    await writeOutputs(outputs);
    mark('outputs written');
    const outcome = { spp: result.spp, seconds: result.seconds, width, height, files: outputs.map((f) => f.path) };
    ctx.stderr.write(`${summaryLine(outcome)}\n`);
    return outcome;
  } finally {
    progress.stop();
  }
}

/**
 * The scene to render and how to read the files it names: a scene file's,
 * or for a model file the scene `pathtrace scene` would print in the
 * current directory (so both render the same), its files named as the user
 * gave them.
 */
async function loadRenderScene(
  file: string,
  raw: RawRenderOptions,
  args: RenderArgs,
  cwd: string | undefined,
): Promise<{ scene: Scene; readFiles: () => Promise<SceneFiles> }> {
  if (!isModelFile(file)) {
    checkNoModelOptions(file, raw);
    const scene = await loadSceneFile(file);
    return { scene, readFiles: () => loadSceneFiles(file, scene) };
  }
  const model = await loadModelScene(file, raw, modelScenePath(file, cwd), args);
  return { scene: model.scene, readFiles: () => loadModelFiles(file, model) };
}

/** Every output path is writable and names a different file (-o first, then --hdr, then --aov). */
async function checkOutputs(pngPath: string, hdrPath: string | undefined, aov: AovPaths | undefined): Promise<void> {
  const outputs: { flag: string; path: string }[] = [{ flag: '-o', path: pngPath }];
  if (hdrPath !== undefined) outputs.push({ flag: '--hdr', path: hdrPath });
  if (aov) outputs.push({ flag: '--aov', path: aov.albedo }, { flag: '--aov', path: aov.normal });
  const problems: string[] = [];
  outputs.forEach(({ flag, path }, i) => {
    const earlier = outputs.slice(0, i).find((o) => resolve(o.path) === resolve(path));
    if (earlier && earlier.flag !== flag) problems.push(`${flag}: ${path} is also the ${earlier.flag} output; give them different names`);
  });
  if (problems.length > 0) throw usageError(problems);
  for (const { flag, path } of outputs) await checkWritable(flag, path);
}

/**
 * Opens a session, runs `work`, and always closes it; `meanwhile` runs while
 * Chromium starts, and its failure (a CliError) ends the wait as Ctrl-C does.
 * Ctrl-C (or SIGTERM) at
 * any point, Chromium's start-up included, ends with exit code 130 after
 * Chromium is closed; Playwright's own signal handlers are off (session.ts).
 */
async function withSession<T>(
  module: SessionModule,
  progress: Progress,
  work: (s: CliSession) => Promise<T>,
  meanwhile?: () => Promise<unknown>,
): Promise<T> {
  progress.status('starting Chromium...');
  const interrupted = interruption();
  const abort = new AbortController();
  const opening = module.openRenderSession({ signal: abort.signal });
  opening.then(() => mark('session open'), () => undefined);
  const never = new Promise<never>(() => undefined);
  const failed = meanwhile ? meanwhile().then(() => never) : never;
  // A bad file stops Chromium's start-up at its next step (after Ctrl-C it completes, then closes).
  failed.catch(() => abort.abort(new Error('a file the scene names is unusable')));
  let session: CliSession | undefined;
  try {
    try {
      session = await Promise.race([opening, interrupted.promise, failed]);
    } catch (error) {
      if (error instanceof CliError) {
        // Interrupted (or a bad file found) while Chromium starts: close it once it is up.
        opening.then((s) => s.close()).catch(() => undefined);
        throw error;
      }
      // ChromiumNotFoundError's message already says how to install Chromium.
      const name = (error as Error | undefined)?.name ?? '';
      const message = SELF_EXPLAINING_ERRORS.has(name) ? oneLine((error as Error).message) : `cannot start Chromium: ${firstLine(error)}`;
      throw failure(message, error);
    }
    const working = work(session);
    working.catch(() => undefined);
    return await Promise.race([working, interrupted.promise]);
  } catch (error) {
    if (error instanceof CliError) throw error;
    throw failure(`render failed: ${firstLine(error)}`, error);
  } finally {
    interrupted.dispose();
    await session?.close().catch(() => undefined);
    mark('session closed');
  }
}

/** Rejects with exit code 130 on SIGINT / SIGTERM, so the session is closed before the process ends. */
function interruption(): { promise: Promise<never>; dispose(): void } {
  let onSignal: () => void = () => undefined;
  const promise = new Promise<never>((_, reject) => {
    onSignal = () => reject(new CliError(EXIT_INTERRUPTED, 'interrupted'));
  });
  promise.catch(() => undefined);
  process.once('SIGINT', onSignal);
  process.once('SIGTERM', onSignal);
  return {
    promise,
    dispose() {
      process.off('SIGINT', onSignal);
      process.off('SIGTERM', onSignal);
    },
  };
}

interface RenderedImages {
  displayed: Uint8Array;
  linear?: Float32Array;
  /** The albedo and normal guides (with --aov). */
  guides?: Guides;
  spp: number;
  seconds: number;
  /** The page's warnings (textures halved to fit the device). */
  warnings?: string[];
}

async function renderImages(
  session: CliSession,
  scene: Scene,
  assets: SceneAssets,
  args: RenderArgs,
  size: { width: number; height: number },
  progress: Progress,
  now: () => number,
  wantLinear: boolean,
): Promise<RenderedImages> {
  progress.status('loading scene and compiling the shader...');
  // Decoded here already (loadSceneFiles): the page takes the arrays and does not decode the files again.
  const loaded = await session.load(scene, { width: size.width, height: size.height, seed: args.seed, ...(args.adaptive ? { adaptive: true } : {}) }, {}, assets);
  // What the mesh decoders ignored (a glTF's unread extensions...), then the page's own.
  const warnings = [...meshWarnings(scene, assets).map((w) => `${w.path}: ${w.message}`), ...(loaded.warnings ?? [])];
  mark('scene loaded in the page');
  progress.start();
  const { spp, seconds } = await renderBudget(session, args.budget, progress, now);
  progress.stop();
  mark('rendered');
  const pixels = size.width * size.height;
  const display = { exposure: args.exposure, toneMap: args.toneMap };
  if (session.readOutputs) {
    if (args.denoise) progress.status('denoising...');
    else if (args.aov) progress.status('rendering the guide buffers...');
    const out = await session.readOutputs({ ...size, display, linear: wantLinear, aovs: args.aov !== undefined, denoise: args.denoise });
    checkLength('displayed image', out.displayed.length, pixels * 4);
    if (wantLinear) checkLength('linear image', out.linear?.length ?? 0, pixels * 4);
    let guides: Guides | undefined;
    if (args.aov) {
      guides = { albedo: out.albedo ?? new Float32Array(0), normal: out.normal ?? new Float32Array(0) };
      checkLength('albedo guide', guides.albedo.length, pixels * 4);
      checkLength('normal guide', guides.normal.length, pixels * 4);
    }
    return { displayed: out.displayed, linear: out.linear, guides, spp, seconds, warnings };
  }
  let guides: Guides | undefined;
  if (args.aov) {
    progress.status('rendering the guide buffers...');
    guides = await readGuides(session, '--aov');
    checkLength('albedo guide', guides.albedo.length, pixels * 4);
    checkLength('normal guide', guides.normal.length, pixels * 4);
  }
  if (args.denoise) {
    progress.status('denoising...');
    const denoised = await denoiseFinalImage(session, size, { exposure: args.exposure, toneMap: args.toneMap }, guides);
    return { ...denoised, guides, spp, seconds, warnings };
  }
  const displayed = await session.readDisplayed({ exposure: args.exposure, toneMap: args.toneMap });
  checkLength('displayed image', displayed.length, pixels * 4);
  let linear: Float32Array | undefined;
  if (wantLinear) {
    linear = await session.readLinear();
    checkLength('linear image', linear.length, pixels * 4);
  }
  return { displayed, linear, guides, spp, seconds, warnings };
}

function checkLength(what: string, got: number, expected: number): void {
  if (got !== expected) throw failure(`render failed: the ${what} has ${got} values, expected ${expected}`);
}

/**
 * Renders until the budget is met: exactly `spp` samples, or as many as fit
 * in `seconds` (at least one). Chunk sizes follow the measured rate.
 */
export async function renderBudget(
  session: Pick<CliSession, 'render'>,
  budget: Budget,
  progress: Pick<Progress, 'update'>,
  now: () => number,
): Promise<{ spp: number; seconds: number }> {
  const start = now();
  let done = 0;
  let chunk = 1;
  let rate = 0;
  for (;;) {
    const elapsed = now() - start;
    let n: number;
    if (budget.kind === 'spp') {
      if (done >= budget.spp) break;
      n = Math.min(chunk, budget.spp - done);
    } else if (done === 0) {
      n = 1;
    } else {
      const fits = Math.floor(rate * (budget.seconds - elapsed));
      if (fits < 1) break;
      n = Math.min(chunk, fits);
    }
    const before = now();
    const total = await session.render(n);
    const took = Math.max(now() - before, 1e-6);
    done = Number.isFinite(total) && total >= done + n ? total : done + n;
    rate = n / took;
    chunk = Math.max(1, Math.min(Math.floor(rate * TARGET_CHUNK_SECONDS), chunk * MAX_CHUNK_GROWTH));
    // The bar shows the mean rate so far: steadier than the last chunk's.
    const sinceStart = now() - start;
    progress.update({ spp: done, elapsed: sinceStart, sppPerSecond: sinceStart > 0 ? done / sinceStart : rate });
  }
  return { spp: done, seconds: now() - start };
}

export function summaryLine(outcome: RenderOutcome): string {
  const { spp, seconds, width, height, files } = outcome;
  const paths = seconds > 0 ? `${formatRate((spp * width * height) / seconds)} paths/s` : '- paths/s';
  return `rendered ${width}x${height} at ${spp} spp in ${seconds.toFixed(2)} s (${paths}) -> ${files.join(', ')}`;
}
