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
}

export interface Denoiser {
  denoise(input: DenoiseInput): Promise<Float32Array>;
  /** "wasm" (the TensorFlow.js backend in use). */
  readonly backend: string;
  dispose(): void;
}

export class DenoiseError extends Error {
  constructor(message: string) {
    super(message);
    this.name = 'DenoiseError';
  }
}

export async function createDenoiser(options: DenoiserOptions = {}): Promise<Denoiser> {
  const backend = await ensureWasmBackend();
  const buffer = await loadWeights(options.weights);
  const unet = new UNet(parseTza(buffer));
  const clamp = options.clampInput;
  if (clamp !== undefined && !(clamp > 0)) throw new DenoiseError(`clampInput: must be a positive number (got ${clamp})`);
  return {
    backend,
    async denoise(input) {
      const channels = checkInput(input);
      const tensor = packInput(input, channels, clamp);
      const output = unet.run(tensor.input);
      tensor.input.dispose();
      const data = await output.data<'float32'>();
      output.dispose();
      return unpackOutput(data, input, channels, tensor);
    },
    dispose() {
      unet.dispose();
    },
  };
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

interface Packed {
  input: tf.Tensor4D;
  paddedWidth: number;
  inputScale: number;
}

/** OIDN's input processing, zero-padded to a multiple of 16 (as OIDN pads its tiles). */
function packInput(input: DenoiseInput, channels: number, clamp: number | undefined): Packed {
  const { width, height, color, albedo, normal } = input;
  const paddedWidth = Math.ceil(width / UNET_ALIGNMENT) * UNET_ALIGNMENT;
  const paddedHeight = Math.ceil(height / UNET_ALIGNMENT) * UNET_ALIGNMENT;
  const source = clamp === undefined ? color : color.map((v) => Math.min(v, clamp));
  const inputScale = autoexposure(source, width, height, channels);
  const data = new Float32Array(paddedWidth * paddedHeight * UNET_INPUT_CHANNELS);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const s = (y * width + x) * channels;
      const d = (y * paddedWidth + x) * UNET_INPUT_CHANNELS;
      for (let c = 0; c < 3; c++) {
        data[d + c] = colorForward(source[s + c], inputScale);
        data[d + 3 + c] = albedoInput(albedo[s + c]);
        data[d + 6 + c] = normalInput(normal[s + c]);
      }
    }
  }
  return { input: tf.tensor4d(data, [1, paddedHeight, paddedWidth, UNET_INPUT_CHANNELS]), paddedWidth, inputScale };
}

function unpackOutput(data: Float32Array, input: DenoiseInput, channels: number, packed: Packed): Float32Array {
  const { width, height, color } = input;
  const out = new Float32Array(width * height * channels);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const s = (y * packed.paddedWidth + x) * 3;
      const d = (y * width + x) * channels;
      for (let c = 0; c < 3; c++) out[d + c] = colorInverse(data[s + c], packed.inputScale);
      if (channels === 4) out[d + 3] = color[d + 3];
    }
  }
  return out;
}
