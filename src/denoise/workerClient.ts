/**
 * createDenoiserWorker(): the same Denoiser as createDenoiser(), running in
 * a dedicated worker so that the page stays responsive while the network
 * runs (seconds on the CPU). Calls are answered in order; the input arrays
 * are copied, not transferred (the caller keeps them).
 */
import type { Denoiser, DenoiserOptions } from './denoiser';
import { DenoiseError } from './errors';

interface Reply {
  id: number;
  backend?: string;
  data?: Float32Array;
  error?: string;
  name?: string;
}

export async function createDenoiserWorker(options: DenoiserOptions = {}): Promise<Denoiser> {
  if (typeof Worker === 'undefined') throw new DenoiseError('denoiser: no backend available: this context has no Web Workers');
  const worker = new Worker(new URL('./worker.ts', import.meta.url), { type: 'module' });
  const pending = new Map<number, { resolve: (reply: Reply) => void; reject: (error: Error) => void }>();
  let next = 0;
  worker.onmessage = (event: MessageEvent<Reply>) => {
    const waiter = pending.get(event.data.id);
    pending.delete(event.data.id);
    if (!waiter) return;
    if (event.data.error !== undefined) waiter.reject(Object.assign(new DenoiseError(event.data.error), { name: event.data.name ?? 'DenoiseError' }));
    else waiter.resolve(event.data);
  };
  worker.onerror = (event) => {
    const error = new DenoiseError(`denoiser worker failed: ${event.message || 'could not start'}`);
    for (const waiter of pending.values()) waiter.reject(error);
    pending.clear();
  };
  const ask = (message: object) =>
    new Promise<Reply>((resolve, reject) => {
      const id = next++;
      pending.set(id, { resolve, reject });
      worker.postMessage({ id, ...message });
    });
  try {
    const { backend } = await ask({ init: options });
    return {
      backend: backend ?? 'unknown',
      async denoise(input) {
        return (await ask({ input })).data!;
      },
      dispose() {
        worker.terminate();
      },
    };
  } catch (error) {
    worker.terminate();
    throw error;
  }
}
