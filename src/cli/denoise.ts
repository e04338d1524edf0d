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

/** The guide buffers (RGBA float32, rows top to bottom), as RenderSession.readAovs gives them. */
export interface Guides {
  albedo: Float32Array;
  normal: Float32Array;
}

/** The tracer's albedo and normal guides (for --denoise and --aov). */
export async function readGuides(session: Partial<DenoiseSession>, flag: string): Promise<Guides> {
  if (!session.readAovs) throw failure(`${flag}: this renderer page has no guide buffers (rebuild with "npm run build")`);
  const { albedo, normal } = await session.readAovs();
  return { albedo, normal };
}

export async function denoiseFinalImage(
  session: Partial<DenoiseSession> & Pick<RenderSession, 'readLinear'>,
  size: { width: number; height: number },
  display: { exposure: number; toneMap: string },
  guides?: Guides,
): Promise<DenoisedImages> {
  const { readAovs, denoise, displayLinear } = session;
  if (!readAovs || !denoise || !displayLinear) throw failure('--denoise: this renderer page cannot denoise (rebuild with "npm run build")');
  const color = await session.readLinear();
  const { albedo, normal } = guides ?? (await readGuides(session, '--denoise'));
  const { width, height } = size;
  const { data } = await denoise.call(session, { width, height, color, albedo, normal });
  if (data.length !== width * height * 4) throw failure(`--denoise: the denoiser returned ${data.length} values, expected ${width * height * 4}`);
  const displayed = await displayLinear.call(session, data, width, height, display);
  return { displayed, linear: data };
}
