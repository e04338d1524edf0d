export { decodeEnvironmentMap, zeroInvalidTexels, MAX_ENVIRONMENT_WIDTH, MAX_ENVIRONMENT_HEIGHT } from './decode';
export {
  buildEnvironmentDistribution,
  sampleEnvironmentDistribution,
  environmentDistributionPdf,
  environmentDistributionPdfUv,
} from './distribution';
export type { EnvironmentDistribution, EnvironmentUvSample, DistributionOptions } from './distribution';
export { directionToUv, uvToDirection, lookupEnvironment } from './mapping';
