export { AOV_SAMPLES, DEFAULT_PATHS_PER_DRAW, PathTracer, type Aovs, type PathTracerOptions } from './PathTracer';
export type { DisplayOptions } from './passes/display';
export { TONEMAPS, type ToneMap } from './toneMaps';
export { ShaderCompileError } from './gl/program';
export { WebGLUnavailableError } from './gl/context';
export { packScene } from './packScene';
