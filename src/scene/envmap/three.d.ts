// The pieces of three.js that src/scene/envmap/exr.ts (and
// bench/envmap-load.ts's writer) use, typed narrowly here rather than pulling in @types/three.
declare module 'three' {
  export const FloatType: number;
  export const DataUtils: { toHalfFloat(value: number): number };
}
