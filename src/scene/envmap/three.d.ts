// The pieces of three.js the OpenEXR decoder (and bench/envmap-load.ts's
// writer) use, typed narrowly here rather than pulling in @types/three.
declare module 'three/examples/jsm/loaders/EXRLoader.js' {
  export class EXRLoader {
    setDataType(type: number): this;
    parse(buffer: ArrayBuffer): { width: number; height: number; data: Float32Array | Uint16Array };
  }
}
declare module 'three' {
  export const FloatType: number;
  export const DataUtils: { toHalfFloat(value: number): number };
}
