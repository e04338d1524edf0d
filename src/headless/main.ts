/**
 * The page that the command-line renderer, the benchmark and the browser
 * tests drive through Playwright: the same PathTracer as the interactive
 * page, exposed as `window.pathtrace` with transfer-friendly results.
 */
import { DEFAULT_PATHS_PER_DRAW, PathTracer } from '../render/PathTracer';
import type { DisplayOptions } from '../render/passes/display';
import type { SamplerKind } from '../render/sampling';
import { loadSceneAssets, NO_ASSETS, type SceneAssets } from '../scene/assets';
import { unpackAssets, type AssetManifest } from '../node/assetTransfer';
import { decodeImageOffThread } from '../render/images/decodeImages';
import type { Scene } from '../scene/types';
import { runKernel, type KernelRequest } from './kernels';
// Registers window.pathtraceEnvironmentKernels (environment-map test kernels).
import './environmentKernels';
import { createContext } from '../render/gl/context';
import { Program, ShaderCompileError } from '../render/gl/program';
import { sceneDefines } from '../render/shaderChunks';
import { SCENE_CHUNKS, VERTEX_CHUNKS } from '../render/shaderSources';
import './bvhKernels'; // window.pathtraceBvh: the BVH traversal kernel for test/browser/bvh-*.test.ts
import './textureKernels'; // window.pathtraceTextureKernels: the texture lookup kernel for test/browser/texture-lookup.test.ts
import './imageDecoding'; // window.pathtraceImages: the texture image Worker, for test/browser/texture-decode.test.ts
import { denoiseArrays, denoiseImage, fromBase64, type DenoiseRequest, type DenoiseResult } from './denoise';
import { displayLinear } from './displayLinear';

export interface LoadOptions {
  width: number;
  height: number;
  seed: number;
  sampler?: SamplerKind;
  russianRoulette?: boolean;
  /** Adaptive sampling (PathTracerOptions.adaptive). */
  adaptive?: boolean;
  /** Accumulate the denoiser's guides while rendering (PathTracerOptions.aovs). */
  aovs?: boolean;
}

/** What load reports: the renderer, the textures' GPU bytes and their warnings (images halved to fit the device). */
export interface LoadResult {
  renderer: string;
  textureBytes?: number;
  warnings?: string[];
}

/** What readOutputs returns, and for what. */
export interface OutputRequest {
  /** The image's size (the tracer's). */
  width: number;
  height: number;
  display: DisplayOptions;
  /** Return the linear image (denoised with `denoise`). */
  linear: boolean;
  /** Return the guides (albedo, normal). */
  aovs: boolean;
  /** Denoise the final image here (src/denoise with the tracer's guides); `displayed` and `linear` are then of the denoised image. */
  denoise: boolean;
}

export interface OutputResult {
  /** Base64 RGBA8 sRGB, as readDisplayed. */
  displayed: string;
  /** Base64 float32 RGBA, as readLinear; with `linear`. */
  linear?: string;
  /** Base64 float32 RGBA, as readAovs; with `aovs`. */
  albedo?: string;
  normal?: string;
}

export interface HeadlessApi {
  /** Capabilities of this browser, checked by every browser test first. */
  probe(): { webgl2: boolean; floatTargets: boolean; renderer: string };
  /**
   * `files`: the bytes (base64) of the files the scene names, by name as
   * written; decoded here. `decoded`: files decoded already (by Node), as a
   * block this page fetches from the session's server (src/node/assetTransfer.ts).
   */
  load(scene: Scene, options: LoadOptions, files?: Record<string, string>, decoded?: AssetManifest): Promise<LoadResult>;
  /**
   * Renders `samples` more spp in draws of `samplesPerDraw` and at most
   * `pathsPerDraw` paths (PathTracer.pathsPerDraw; unchanged when omitted),
   * waits for the GPU.
   */
  render(samples: number, samplesPerDraw: number, pathsPerDraw?: number): { sampleCount: number; milliseconds: number };
  /**
   * PathTracer.renderPaths: about `paths` more paths (a part of a sample when
   * fewer than the image's pixels); does not wait for the GPU.
   */
  renderPaths(paths: number): { traced: number; sampleCount: number; sampleProgress: number };
  /** Discards the accumulated samples (keeps the compiled shaders: for timing). */
  reset(): void;
  readLinear(): string;
  /** PathTracer.readAovs: each guide as base64 float32, and the samples behind them. */
  readAovs(): { albedo: string; normal: string; samples: number };
  readDisplayed(options: DisplayOptions): string;
  loseContext(): void;
  restoreContext(): void;
  contextLost(): boolean;
  runKernel(request: KernelRequest): string;
  /** Compiles `source` as a fragment-shader chunk named `name` after the common chunks; the error log, or null. */
  compileLog(name: string, source: string): string | null;
  /** Denoises base64 float32 arrays handed in (src/headless/denoise.ts). */
  denoise(request: DenoiseRequest): Promise<DenoiseResult>;
  /** A linear RGBA image (base64 float32) through the display pass: base64 RGBA8 sRGB. */
  displayLinear(linear: string, width: number, height: number, options: DisplayOptions): string;
  /**
   * The CLI's images in one call, each leaving the page once: with
   * `denoise`, the linear image and the guides go to the denoiser and the
   * display pass here, instead of through Node (readLinear, readAovs,
   * denoise, displayLinear).
   */
  readOutputs(request: OutputRequest): Promise<OutputResult>;
}

let tracer: PathTracer | null = null;
/** The options `tracer` was made with that only a new PathTracer can change. */
let tracerKind = '';
let loseContextExtension: WEBGL_lose_context | null = null;

/**
 * A loaded scene goes to the tracer already here when its kind allows: the
 * same context keeps its compiled programs, and SwiftShader compiles a
 * program at its first draw in each new context (~0.5 s for a sphere scene,
 * ~1.8 s for a mesh scene), a cost that tests rendering a scene in several
 * seeded batches would otherwise pay per batch. The result is the same
 * bits: an image depends only on scene, size, seed and sample indices.
 */
function reuseTracer(scene: Scene, options: LoadOptions, assets: Awaited<ReturnType<typeof loadSceneAssets>>, kind: string): boolean {
  if (!tracer || tracer.contextLost || kind !== tracerKind) return false;
  tracer.pathsPerDraw = DEFAULT_PATHS_PER_DRAW;
  tracer.setAovs(options.aovs ?? false);
  tracer.setSize(options.width, options.height);
  tracer.setSeed(options.seed);
  tracer.setScene(scene, assets);
  return true;
}

/**
 * The files of the last load, as sent and as decoded: a load that sends the
 * same bytes again (a test rendering one scene in seeded batches) reuses
 * the decoded data, so the renderer keeps its BVH and map distribution
 * instead of decoding and building them anew for every batch.
 */
let lastFiles: { texts: Record<string, string>; assets: SceneAssets } | null = null;

function sameFiles(files: Record<string, string>): SceneAssets {
  if (!lastFiles) return NO_ASSETS;
  const { texts, assets } = lastFiles;
  const same = (name: string) => texts[name] !== undefined && texts[name] === files[name];
  return {
    maps: new Map([...assets.maps].filter(([name]) => same(name))),
    meshes: new Map([...assets.meshes].filter(([name]) => same(name))),
    images: new Map([...(assets.images ?? [])].filter(([name]) => same(name))),
  };
}

function rememberFiles(files: Record<string, string>, assets: SceneAssets): void {
  lastFiles = { texts: files, assets };
}

function requireTracer(): PathTracer {
  if (!tracer) throw new Error('no scene loaded');
  return tracer;
}


function bytesFromBase64(text: string): Uint8Array {
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
  return bytes;
}

async function fetchBlock(url: string): Promise<ArrayBuffer> {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`cannot fetch the decoded assets (${url}): HTTP ${response.status}`);
  return response.arrayBuffer();
}

function toBase64(bytes: Uint8Array): string {
  let binary = '';
  const chunk = 0x8000;
  for (let i = 0; i < bytes.length; i += chunk) {
    binary += String.fromCharCode(...bytes.subarray(i, i + chunk));
  }
  return btoa(binary);
}

const api: HeadlessApi = {
  probe() {
    const gl = new OffscreenCanvas(1, 1).getContext('webgl2');
    const floatTargets = !!gl?.getExtension('EXT_color_buffer_float');
    const debug = gl?.getExtension('WEBGL_debug_renderer_info');
    const renderer = gl && debug ? String(gl.getParameter(debug.UNMASKED_RENDERER_WEBGL)) : '';
    return { webgl2: !!gl, floatTargets, renderer };
  },
  async load(scene, options, files = {}, decoded) {
    const known = decoded ? unpackAssets(decoded, await fetchBlock(decoded.url)) : sameFiles(files);
    const assets = await loadSceneAssets(scene, async (name) => {
      const encoded = known.encodedImages?.get(name);
      if (encoded) return encoded;
      if (!(name in files)) throw new Error('no such file was given to the page');
      return bytesFromBase64(files[name]);
    }, known, decodeImageOffThread);
    rememberFiles(files, assets);
    const kind = JSON.stringify([options.sampler ?? 'kronecker', options.russianRoulette ?? false, options.adaptive ?? false]);
    if (!reuseTracer(scene, options, assets, kind)) {
      tracer?.dispose();
      tracer = new PathTracer(undefined, scene, { ...options, assets });
      tracerKind = kind;
      loseContextExtension = tracer.gl.getExtension('WEBGL_lose_context');
    }
    const textures = tracer!.textures;
    return { renderer: tracer!.renderer, textureBytes: textures.bytes, warnings: [...textures.warnings] };
  },
  render(samples, samplesPerDraw, pathsPerDraw) {
    const t = requireTracer();
    if (pathsPerDraw !== undefined) t.pathsPerDraw = pathsPerDraw;
    const start = performance.now();
    t.render(samples, samplesPerDraw);
    t.finish();
    return { sampleCount: t.sampleCount, milliseconds: performance.now() - start };
  },
  renderPaths(paths) {
    const t = requireTracer();
    const traced = t.renderPaths(paths);
    return { traced, sampleCount: t.sampleCount, sampleProgress: t.sampleProgress };
  },
  reset() {
    requireTracer().reset();
  },
  readLinear() {
    const data = requireTracer().readLinear();
    return toBase64(new Uint8Array(data.buffer, data.byteOffset, data.byteLength));
  },
  readAovs() {
    const { albedo, normal, samples } = requireTracer().readAovs();
    const encode = (data: Float32Array) => toBase64(new Uint8Array(data.buffer, data.byteOffset, data.byteLength));
    return { albedo: encode(albedo), normal: encode(normal), samples };
  },
  readDisplayed(options) {
    return toBase64(requireTracer().readDisplayed(options));
  },
  loseContext() {
    loseContextExtension?.loseContext();
  },
  restoreContext() {
    loseContextExtension?.restoreContext();
  },
  contextLost() {
    return requireTracer().contextLost;
  },
  runKernel(request) {
    const data = runKernel(request);
    return toBase64(new Uint8Array(data.buffer, data.byteOffset, data.byteLength));
  },
  compileLog(name, source) {
    const gl = createContext(new OffscreenCanvas(1, 1), false);
    try {
      new Program(gl, VERTEX_CHUNKS, [...SCENE_CHUNKS.slice(0, 3), { name, source }], sceneDefines()).dispose();
      return null;
    } catch (error) {
      if (error instanceof ShaderCompileError) return error.message;
      throw error;
    }
  },
  denoise: denoiseArrays,
  displayLinear(linear, width, height, options) {
    return toBase64(displayLinear(fromBase64(linear), width, height, options));
  },
  async readOutputs({ width, height, display, linear, aovs, denoise }) {
    const t = requireTracer();
    const floats = (data: Float32Array) => toBase64(new Uint8Array(data.buffer, data.byteOffset, data.byteLength));
    // The same calls in the same order as the CLI made them through Node.
    let guides = aovs ? t.readAovs() : undefined;
    const result: OutputResult = { displayed: '' };
    if (guides) {
      result.albedo = floats(guides.albedo);
      result.normal = floats(guides.normal);
    }
    if (denoise) {
      const color = t.readLinear();
      guides ??= t.readAovs();
      const { data } = await denoiseImage({ width, height, color, albedo: guides.albedo, normal: guides.normal });
      if (data.length !== width * height * 4) throw new Error(`the denoiser returned ${data.length} values, expected ${width * height * 4}`);
      result.displayed = toBase64(displayLinear(data, width, height, display));
      if (linear) result.linear = floats(data);
    } else {
      result.displayed = toBase64(t.readDisplayed(display));
      if (linear) result.linear = floats(t.readLinear());
    }
    return result;
  },
};

declare global {
  interface Window {
    pathtrace: HeadlessApi;
  }
}

window.pathtrace = api;
document.body.dataset.ready = 'true';
