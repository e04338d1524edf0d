/**
 * Open Image Denoise's trained U-Net (HDR colour + albedo + normal guides)
 * in the browser, on TensorFlow.js's WebAssembly backend (XNNPACK, SIMD).
 *
 *   const denoiser = await createDenoiser();
 *   const clean = await denoiser.denoise({ width, height, color, albedo, normal });
 *
 * Arrays are linear float RGB or RGBA, rows top to bottom (as
 * PathTracer.readLinear() returns); the result has the colour's layout, its
 * alpha copied. Why WebAssembly and not the GPU: on machines without a GPU
 * (SwiftShader) the WebGL and WebGPU networks take 80-150 s for 256x192,
 * WebAssembly about 1 s (bench/results/denoise-2026-11-28.md).
 *
 * Pages should use createDenoiserWorker() (same interface): the network
 * runs for seconds, and this project's pages forbid WebAssembly compilation
 * in their CSP (no 'wasm-unsafe-eval'); a same-origin worker has no CSP.
 */
import * as tf from '@tensorflow/tfjs-core';
import { UNet, UNET_ALIGNMENT, UNET_INPUT_CHANNELS } from './unet';
import { parseTza } from './tza';
import { albedoInput, autoexposure, colorForward, colorInverse, normalInput } from './transfer';
import { ensureWasmBackend } from './backend';
import { DenoiseError } from './errors';

export interface DenoiseInput {
  width: number;
  height: number;
  /** Linear HDR radiance, RGB or RGBA, rows top to bottom. */
  color: Float32Array;
  /** Albedo of the first non-specular hit, in [0, 1] (OIDN's convention); same layout as color. */
  albedo: Float32Array;
  /** World-space normal of the first non-specular hit, in [-1, 1]; same layout as color. */
  normal: Float32Array;
}

export interface DenoiserOptions {
  /** The TZA weights (rt_hdr_alb_nrm): bytes, or a URL; default: the bundled file. */
  weights?: ArrayBuffer | string;
  /**
   * Clamp the colour the network sees to this value (after nothing else):
   * tames fireflies. Only the denoiser's input: the saved HDR is never
   * clamped. Default: no clamp.
   */
  clampInput?: number;
  /**
   * Largest tile edge the network sees at once (default 512): larger images
   * run as tiles with a 96-pixel overlap (half OIDN's receptive field,
   * rounded to 16, as OIDN tiles), which bounds memory and the time of one
   * call. Multiple of 16, at least 256.
   */
  maxTileSize?: number;
}

export interface Denoiser {
  denoise(input: DenoiseInput): Promise<Float32Array>;
  /** "wasm" (the TensorFlow.js backend in use). */
  readonly backend: string;
  dispose(): void;
}

export { DenoiseError };

export async function createDenoiser(options: DenoiserOptions = {}): Promise<Denoiser> {
  const clamp = options.clampInput;
  if (clamp !== undefined && !(clamp > 0)) throw new DenoiseError(`clampInput: must be a positive number (got ${clamp})`);
  const maxTile = options.maxTileSize ?? DEFAULT_MAX_TILE;
  if (!Number.isInteger(maxTile) || maxTile % UNET_ALIGNMENT !== 0 || maxTile < 2 * TILE_OVERLAP + 64) {
    throw new DenoiseError(`maxTileSize: must be a multiple of ${UNET_ALIGNMENT}, at least ${2 * TILE_OVERLAP + 64} (got ${maxTile})`);
  }
  const backend = await ensureWasmBackend();
  const unet = new UNet(parseTza(await loadWeights(options.weights)));
  return {
    backend,
    async denoise(input) {
      const channels = checkInput(input);
      const color = clamp === undefined ? input.color : input.color.map((v) => Math.min(v, clamp));
      const image = { ...input, color, channels, inputScale: autoexposure(color, input.width, input.height, channels) };
      const out = new Float32Array(input.width * input.height * channels);
      for (const tile of tiles(input.width, input.height, maxTile)) {
        const tensor = packTile(image, tile.source);
        const result = unet.run(tensor.input);
        tensor.input.dispose();
        const data = await result.data<'float32'>();
        result.dispose();
        unpackTile(data, image, tensor.paddedWidth, tile, out);
      }
      return out;
    },
    dispose() {
      unet.dispose();
    },
  };
}

const DEFAULT_MAX_TILE = 512;
/** Half of OIDN's receptive field (174 small, 202 large), rounded up to 16, as OIDN overlaps its tiles. */
const TILE_OVERLAP = 96;

interface Rect {
  x: number;
  y: number;
  width: number;
  height: number;
}

/** Output rectangles covering the image, each with the source rectangle (output + overlap, inside the image) it needs. */
export function tiles(width: number, height: number, maxTile: number): { output: Rect; source: Rect }[] {
  if (width <= maxTile && height <= maxTile) {
    const all = { x: 0, y: 0, width, height };
    return [{ output: all, source: all }];
  }
  const step = maxTile - 2 * TILE_OVERLAP;
  const result: { output: Rect; source: Rect }[] = [];
  for (let y = 0; y < height; y += step) {
    for (let x = 0; x < width; x += step) {
      const output = { x, y, width: Math.min(step, width - x), height: Math.min(step, height - y) };
      const x0 = Math.max(0, x - TILE_OVERLAP);
      const y0 = Math.max(0, y - TILE_OVERLAP);
      const x1 = Math.min(width, x + output.width + TILE_OVERLAP);
      const y1 = Math.min(height, y + output.height + TILE_OVERLAP);
      result.push({ output, source: { x: x0, y: y0, width: x1 - x0, height: y1 - y0 } });
    }
  }
  return result;
}

async function loadWeights(weights: ArrayBuffer | string | undefined): Promise<ArrayBuffer> {
  if (weights instanceof ArrayBuffer) return weights;
  const url = weights ?? (await import('./weightsUrl')).DEFAULT_WEIGHTS_URL;
  const response = await fetch(url);
  if (!response.ok) throw new DenoiseError(`weights: cannot load ${url} (HTTP ${response.status})`);
  return response.arrayBuffer();
}

function checkInput(input: DenoiseInput): number {
  const { width, height } = input;
  if (!Number.isInteger(width) || width < 1) throw new DenoiseError(`width: must be a positive integer (got ${width})`);
  if (!Number.isInteger(height) || height < 1) throw new DenoiseError(`height: must be a positive integer (got ${height})`);
  const pixels = width * height;
  const channels = input.color?.length / pixels;
  if (channels !== 3 && channels !== 4) {
    throw new DenoiseError(`color: expected ${pixels * 3} (RGB) or ${pixels * 4} (RGBA) values for ${width}x${height}, got ${input.color?.length}`);
  }
  for (const name of ['albedo', 'normal'] as const) {
    const array = input[name];
    if (!(array instanceof Float32Array)) throw new DenoiseError(`${name}: must be a Float32Array (the guides are required)`);
    if (array.length !== pixels * channels) throw new DenoiseError(`${name}: expected ${pixels * channels} values like color, got ${array.length}`);
  }
  return channels;
}

interface Image extends DenoiseInput {
  channels: number;
  inputScale: number;
}

interface Packed {
  input: tf.Tensor4D;
  paddedWidth: number;
}

/** OIDN's input processing of one source rectangle, zero-padded to a multiple of 16 (as OIDN pads its tiles). */
function packTile(image: Image, rect: Rect): Packed {
  const { width, color, albedo, normal, channels, inputScale } = image;
  const paddedWidth = Math.ceil(rect.width / UNET_ALIGNMENT) * UNET_ALIGNMENT;
  const paddedHeight = Math.ceil(rect.height / UNET_ALIGNMENT) * UNET_ALIGNMENT;
  const data = new Float32Array(paddedWidth * paddedHeight * UNET_INPUT_CHANNELS);
  for (let y = 0; y < rect.height; y++) {
    for (let x = 0; x < rect.width; x++) {
      const s = ((rect.y + y) * width + rect.x + x) * channels;
      const d = (y * paddedWidth + x) * UNET_INPUT_CHANNELS;
      for (let c = 0; c < 3; c++) {
        data[d + c] = colorForward(color[s + c], inputScale);
        data[d + 3 + c] = albedoInput(albedo[s + c]);
        data[d + 6 + c] = normalInput(normal[s + c]);
      }
    }
  }
  return { input: tf.tensor4d(data, [1, paddedHeight, paddedWidth, UNET_INPUT_CHANNELS]), paddedWidth };
}

/** Writes the tile's output rectangle (alpha from the colour) into `out`. */
function unpackTile(data: Float32Array, image: Image, paddedWidth: number, tile: { output: Rect; source: Rect }, out: Float32Array): void {
  const { width, color, channels, inputScale } = image;
  const { output, source } = tile;
  for (let y = output.y; y < output.y + output.height; y++) {
    for (let x = output.x; x < output.x + output.width; x++) {
      const s = ((y - source.y) * paddedWidth + (x - source.x)) * 3;
      const d = (y * width + x) * channels;
      for (let c = 0; c < 3; c++) out[d + c] = colorInverse(data[s + c], inputScale);
      if (channels === 4) out[d + 3] = color[d + 3];
    }
  }
}
