/**
 * TensorFlow.js's WebAssembly backend with its binaries bundled by Vite
 * (never fetched from a CDN). Always single-threaded SIMD: the threaded
 * build's workers importScripts() the unbundled tfjs script, which a Vite
 * bundle does not have (tried on a cross-origin-isolated page: the workers
 * fail), so threads are switched off and that binary is not shipped.
 * Run several denoisers (createDenoiserWorker) for parallelism instead.
 */
import * as tf from '@tensorflow/tfjs-core';
import { setWasmPaths } from '@tensorflow/tfjs-backend-wasm';
import plain from '@tensorflow/tfjs-backend-wasm/dist/tfjs-backend-wasm.wasm?url';
import simd from '@tensorflow/tfjs-backend-wasm/dist/tfjs-backend-wasm-simd.wasm?url';

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
    // Required by setWasmPaths, never loaded: multithreading is off below.
    'tfjs-backend-wasm-threaded-simd.wasm': simd,
  });
  tf.env().set('WASM_HAS_MULTITHREAD_SUPPORT', false);
  if (!(await tf.setBackend('wasm'))) throw new Error('tf.setBackend("wasm") failed');
  await tf.ready();
  return tf.getBackend();
}
