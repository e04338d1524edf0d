/**
 * The page's off-thread image decoder (src/render/images/decodeImages.ts)
 * for unit tests in Node, where there is no Worker: the same decoder on the
 * calling thread. `vi.mock('../../src/render/images/decodeImages', () =>
 * import('../support/nodeImageDecoder'))`.
 */
import { decodeTextureImage } from '../../src/scene/texture/decode';

export const decodeImageOffThread = (bytes: Uint8Array) => decodeTextureImage(bytes);
