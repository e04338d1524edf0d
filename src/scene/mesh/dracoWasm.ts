/**
 * The Draco decoder's WebAssembly for the browser, as a file URL the bundler
 * emits (Node's build finds its .wasm beside the module by itself). Loaded by
 * gltf.ts only in a browser and only for Draco-compressed files.
 */
import wasmUrl from 'draco3dgltf/draco_decoder_gltf.wasm?url';

export async function dracoWasmBinary(): Promise<ArrayBuffer> {
  const response = await fetch(wasmUrl);
  if (!response.ok) throw new Error(`cannot load the Draco decoder (${response.status} ${wasmUrl})`);
  return response.arrayBuffer();
}
