// Types of the vendored EXRLoader (only what src/scene/envmap/exr.ts uses).
export class EXRLoader {
  setDataType(type: number): this;
  parse(buffer: ArrayBuffer): { width: number; height: number; data: Float32Array | Uint16Array };
}
