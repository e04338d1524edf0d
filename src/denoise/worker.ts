/**
 * The denoiser in a dedicated worker (see workerClient.ts): the network
 * runs for seconds on the CPU, so the page's main thread must not run it.
 * Messages: { id, init: DenoiserOptions } -> { id, backend };
 * { id, input: DenoiseInput } -> { id, data } (buffers transferred);
 * failures -> { id, error }.
 */
import { createDenoiser, type Denoiser } from './denoiser';

let denoiser: Promise<Denoiser> | undefined;

const scope = self as unknown as { postMessage(message: unknown, transfer?: Transferable[]): void; onmessage: ((event: MessageEvent) => void) | null };

scope.onmessage = async (event: MessageEvent) => {
  const { id, init, input } = event.data as { id: number; init?: Parameters<typeof createDenoiser>[0]; input?: Parameters<Denoiser['denoise']>[0] };
  try {
    if (init) {
      denoiser = createDenoiser(init);
      scope.postMessage({ id, backend: (await denoiser).backend });
    } else if (input) {
      if (!denoiser) throw new Error('denoiser worker: not initialized');
      const data = await (await denoiser).denoise(input);
      scope.postMessage({ id, data }, [data.buffer]);
    }
  } catch (error) {
    scope.postMessage({ id, error: (error as Error)?.message ?? String(error), name: (error as Error)?.name });
  }
};
