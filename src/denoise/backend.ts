/**
 * TensorFlow.js's WebAssembly backend with its binaries bundled by Vite
 * (never fetched from a CDN). Single-threaded SIMD unless the page is
 * cross-origin isolated (then XNNPACK's threaded build is used).
 */
import * as tf from '@tensorflow/tfjs-core';
import { setWasmPaths } from '@tensorflow/tfjs-backend-wasm';
import plain from '@tensorflow/tfjs-backend-wasm/dist/tfjs-backend-wasm.wasm?url';
import simd from '@tensorflow/tfjs-backend-wasm/dist/tfjs-backend-wasm-simd.wasm?url';
import threaded from '@tensorflow/tfjs-backend-wasm/dist/tfjs-backend-wasm-threaded-simd.wasm?url';

let ready: Promise<string> | undefined;

export function ensureWasmBackend(): Promise<string> {
  ready ??= init().catch((error: unknown) => {
    ready = undefined;
    throw new Error(`denoiser: no backend available: WebAssembly could not start (${(error as Error)?.message ?? error})`);
  });
  return ready;
}

async function init(): Promise<string> {
  if (typeof WebAssembly !== 'object') throw new Error('this browser has no WebAssembly');
  setWasmPaths({
    'tfjs-backend-wasm.wasm': plain,
    'tfjs-backend-wasm-simd.wasm': simd,
    'tfjs-backend-wasm-threaded-simd.wasm': threaded,
  });
  if (!(await tf.setBackend('wasm'))) throw new Error('tf.setBackend("wasm") failed');
  await tf.ready();
  return tf.getBackend();
}
