/**
 * The texture image Worker: decodes image files off the page's main thread
 * (a 2048 x 2048 PNG takes a noticeable time to inflate and unfilter, see
 * decodeImages.ts) and transfers the texels back.
 */
import { AssetError } from '../../scene/assetError';
import { decodeTextureImage } from '../../scene/texture/decode';
import { bitmapDecoder } from './bitmapReadback';
import type { ImageWorkerReply, ImageWorkerRequest } from './decodeImages';

self.onmessage = async (event: MessageEvent<ImageWorkerRequest>) => {
  const { id, bytes, readback } = event.data;
  try {
    const start = performance.now();
    const image = await decodeTextureImage(new Uint8Array(bytes), bitmapDecoder(readback));
    const reply: ImageWorkerReply = { id, ok: true, image, decodeMs: performance.now() - start };
    (self as unknown as Worker).postMessage(reply, [image.data.buffer as ArrayBuffer]);
  } catch (error) {
    const reply: ImageWorkerReply = { id, ok: false, message: (error as Error)?.message ?? String(error), assetError: error instanceof AssetError };
    (self as unknown as Worker).postMessage(reply);
  }
};
