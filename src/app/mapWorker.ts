/**
 * The environment-map Worker: decodes a map file and builds its sampling
 * distribution off the page's main thread (a 2k map takes a few hundred
 * milliseconds of CPU, see bench/envmap-load.ts: the page would freeze for
 * that long). Replies with the pixels and the distribution, transferred.
 */
import { AssetError } from '../scene/assetError';
import { buildEnvironmentDistribution, decodeEnvironmentMap } from '../scene/envmap';
import type { MapWorkerReply, MapWorkerRequest } from './mapDecoder';

self.onmessage = (event: MessageEvent<MapWorkerRequest>) => {
  const { id, bytes, name } = event.data;
  try {
    const t0 = performance.now();
    const image = decodeEnvironmentMap(new Uint8Array(bytes), name);
    const t1 = performance.now();
    const distribution = buildEnvironmentDistribution(image);
    const t2 = performance.now();
    const reply: MapWorkerReply = { id, ok: true, image, distribution, decodeMs: t1 - t0, distributionMs: t2 - t1 };
    (self as unknown as Worker).postMessage(reply, [image.rgb.buffer, distribution.marginal.buffer, distribution.conditional.buffer]);
  } catch (error) {
    const reply: MapWorkerReply = { id, ok: false, message: (error as Error)?.message ?? String(error), assetError: error instanceof AssetError };
    (self as unknown as Worker).postMessage(reply);
  }
};
