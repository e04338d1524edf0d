/**
 * The MikkTSpace WebAssembly for the browser, as a file URL the bundler
 * emits (Node reads the same file from node_modules: mikktspace.ts). Loaded
 * only when a tangent frame must be computed.
 */
import wasmUrl from 'mikktspace/dist/module/mikktspace_module_bg.wasm?url';

export async function mikktspaceWasmBinary(): Promise<ArrayBuffer> {
  const response = await fetch(wasmUrl);
  if (!response.ok) throw new Error(`cannot load the MikkTSpace WebAssembly (${response.status} ${wasmUrl})`);
  return response.arrayBuffer();
}
