export { decodeEnvironmentMap, zeroInvalidTexels, MAX_ENVIRONMENT_WIDTH, MAX_ENVIRONMENT_HEIGHT } from './decode';
