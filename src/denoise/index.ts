export { createDenoiser, DenoiseError, type Denoiser, type DenoiseInput, type DenoiserOptions } from './denoiser';
export { WeightsError } from './tza';
export { createDenoiserWorker } from './workerClient';
