/**
 * The headless page's denoiser entry: float32 arrays arrive base64-encoded
 * (Playwright passes JSON), go through src/denoise in a dedicated worker,
 * and leave the same way. The module and its weights load on first use only.
 */
import type { Denoiser, DenoiserOptions } from '../denoise';

export interface DenoiseRequest {
  width: number;
  height: number;
  /** Base64 of float32 RGBA rows, top to bottom. */
  color: string;
  albedo: string;
  normal: string;
  options?: Pick<DenoiserOptions, 'clampInput' | 'maxTileSize'> & {
    /** Base64 of other TZA weights (the benchmark compares OIDN's small network); default: the bundled file. */
    weights?: string;
  };
}

export interface DenoiseResult {
  /** Longest gap between main-thread timer ticks during the call (ms): small when a worker does the work. */
  longestMainThreadGap: number;
  /** Base64 of float32 RGBA rows, top to bottom. */
  data: string;
  /** Time of the denoise call alone (input processing, network, output). */
  milliseconds: number;
  /** Time to create the denoiser (backend start, weights), 0 when cached. */
  setupMilliseconds: number;
  backend: string;
}

const denoisers = new Map<string, Promise<Denoiser>>();

async function denoiserFor(options: DenoiseRequest['options'] = {}): Promise<Denoiser> {
  const key = JSON.stringify(options);
  let denoiser = denoisers.get(key);
  if (!denoiser) {
    // In a worker: the page stays responsive, and the worker (a same-origin
    // script with no CSP of its own) may compile WebAssembly, which the
    // page's CSP rightly forbids ('wasm-unsafe-eval' is not granted).
    const { createDenoiserWorker } = await import('../denoise/workerClient');
    const weights = options.weights === undefined ? undefined : fromBase64(options.weights).buffer as ArrayBuffer;
    denoiser = createDenoiserWorker({ clampInput: options.clampInput, maxTileSize: options.maxTileSize, weights });
    denoiser.catch(() => denoisers.delete(key));
    denoisers.set(key, denoiser);
  }
  return denoiser;
}

/** Float32 RGBA rows, top to bottom, width*height*4 each: what denoiseImage takes. */
export interface DenoiseImages {
  width: number;
  height: number;
  color: Float32Array;
  albedo: Float32Array;
  normal: Float32Array;
}

/** Denoises arrays already in the page (readOutputs: the CLI's --denoise); the result as DenoiseResult, not encoded. */
export async function denoiseImage(images: DenoiseImages, options?: DenoiseRequest['options']): Promise<Omit<DenoiseResult, 'data'> & { data: Float32Array }> {
  const setupStart = performance.now();
  const denoiser = await denoiserFor(options);
  const start = performance.now();
  const watch = watchMainThread();
  const data = await denoiser.denoise(images);
  const end = performance.now();
  const longestMainThreadGap = watch.stop();
  return { data, milliseconds: end - start, setupMilliseconds: start - setupStart, backend: denoiser.backend, longestMainThreadGap };
}

export async function denoiseArrays(request: DenoiseRequest): Promise<DenoiseResult> {
  const { width, height } = request;
  const images = { width, height, color: fromBase64(request.color), albedo: fromBase64(request.albedo), normal: fromBase64(request.normal) };
  const result = await denoiseImage(images, request.options);
  return { ...result, data: toBase64(result.data) };
}

export function fromBase64(text: string): Float32Array {
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
  return new Float32Array(bytes.buffer);
}

export function toBase64(data: Float32Array): string {
  const bytes = new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
  let binary = '';
  for (let i = 0; i < bytes.length; i += 0x8000) binary += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(binary);
}

/** Ticks a 10 ms timer and records the longest gap between ticks (a blocked main thread shows as a long gap). */
function watchMainThread(): { stop(): number } {
  let last = performance.now();
  let longest = 0;
  const timer = setInterval(() => {
    const now = performance.now();
    longest = Math.max(longest, now - last);
    last = now;
  }, 10);
  return {
    stop() {
      clearInterval(timer);
      return Math.max(longest, performance.now() - last);
    },
  };
}
