/**
 * `pathtrace render --denoise`: the final image through src/denoise (OIDN's
 * network) in the page, with the tracer's albedo and normal guides; the
 * PNG is the denoised image through the same display pass, the --hdr PFM
 * the denoised linear image. Without --denoise none of this runs.
 */
import type { RenderSession } from '../node/session';
import { failure } from './errors';

/** What --denoise needs from the session (optional in CliSession: older pages lack it). */
export type DenoiseSession = Pick<RenderSession, 'readLinear' | 'readAovs' | 'denoise' | 'displayLinear'>;

export interface DenoisedImages {
  displayed: Uint8Array;
  linear: Float32Array;
}

export async function denoiseFinalImage(
  session: Partial<DenoiseSession> & Pick<RenderSession, 'readLinear'>,
  size: { width: number; height: number },
  display: { exposure: number; toneMap: string },
): Promise<DenoisedImages> {
  const { readAovs, denoise, displayLinear } = session;
  if (!readAovs || !denoise || !displayLinear) throw failure('--denoise: this renderer page cannot denoise (rebuild with "npm run build")');
  const color = await session.readLinear();
  const { albedo, normal } = await readAovs.call(session);
  const { width, height } = size;
  const { data } = await denoise.call(session, { width, height, color, albedo, normal });
  if (data.length !== width * height * 4) throw failure(`--denoise: the denoiser returned ${data.length} values, expected ${width * height * 4}`);
  const displayed = await displayLinear.call(session, data, width, height, display);
  return { displayed, linear: data };
}
