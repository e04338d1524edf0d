/**
 * The `mikktspace` package's WebAssembly (the gltf-rs port of Mikkelsen's
 * reference C code), instantiated here rather than through the package's
 * entries: its ES entry imports the .wasm as a module with top-level await,
 * which the page's workers (IIFE bundles) cannot hold, and its CommonJS
 * entry is Node only. This speaks the wasm-bindgen ABI of that one export,
 * `generateTangents(positions, normals, uvs)` over unindexed triangles (3, 3
 * and 2 floats per corner), which returns 4 floats (x, y, z, w) per corner.
 */
export type GenerateTangents = (positions: Float32Array, normals: Float32Array, uvs: Float32Array) => Float32Array;

const WASM = 'mikktspace/dist/module/mikktspace_module_bg.wasm';

interface MikkTSpaceExports {
  memory: WebAssembly.Memory;
  generateTangents(result: number, positions: number, positionsLength: number, normals: number, normalsLength: number, uvs: number, uvsLength: number): void;
  __wbindgen_add_to_stack_pointer(delta: number): number;
  __wbindgen_malloc(bytes: number): number;
  __wbindgen_free(pointer: number, bytes: number): void;
}

let generator: Promise<GenerateTangents> | null = null;

/** MikkTSpace, compiled once (a chunk of its own: only scenes with normal maps load it). */
export function loadMikkTSpace(): Promise<GenerateTangents> {
  generator ??= (async () => {
    try {
      return await instantiate(await wasmBytes());
    } catch (error) {
      // In a page whose Content-Security-Policy lacks 'wasm-unsafe-eval', WebAssembly cannot compile (workers can).
      throw new Error(`cannot compute tangent frames: the MikkTSpace WebAssembly cannot run here (${(error as Error)?.message ?? String(error)})`);
    }
  })();
  generator.catch(() => (generator = null)); // a failed load may be retried
  return generator;
}

async function wasmBytes(): Promise<ArrayBuffer | Uint8Array<ArrayBuffer>> {
  if (typeof process !== 'undefined' && !!process.versions?.node) {
    // Specifiers in variables: the browser bundles must not try to resolve Node's modules.
    const [fsModule, moduleModule] = ['node:fs/promises', 'node:module'];
    const { readFile } = (await import(/* @vite-ignore */ fsModule)) as typeof import('node:fs/promises');
    const { createRequire } = (await import(/* @vite-ignore */ moduleModule)) as typeof import('node:module');
    return readFile(createRequire(import.meta.url).resolve(WASM)) as Promise<Uint8Array<ArrayBuffer>>;
  }
  return (await import('./mikktspaceWasm')).mikktspaceWasmBinary();
}

async function instantiate(bytes: ArrayBuffer | Uint8Array<ArrayBuffer>): Promise<GenerateTangents> {
  const module = await WebAssembly.compile(bytes);
  let wasm: MikkTSpaceExports | null = null;
  // The module's only imports: a Rust error becomes a JS string (by handle), then is thrown.
  const thrown = new Map<number, string>();
  const bindings = {
    __wbindgen_string_new: (pointer: number, length: number) => {
      const handle = 64 + thrown.size; // above wasm-bindgen's reserved handles
      thrown.set(handle, new TextDecoder().decode(new Uint8Array(wasm!.memory.buffer, pointer, length)));
      return handle;
    },
    __wbindgen_rethrow: (handle: number) => {
      const message = thrown.get(handle) ?? 'unknown error';
      thrown.clear();
      throw new Error(message);
    },
  };
  const imports: WebAssembly.Imports = {};
  for (const { module: name } of WebAssembly.Module.imports(module)) imports[name] = bindings;
  wasm = (await WebAssembly.instantiate(module, imports)).exports as unknown as MikkTSpaceExports;
  return (positions, normals, uvs) => generate(wasm!, positions, normals, uvs);
}

function generate(wasm: MikkTSpaceExports, positions: Float32Array, normals: Float32Array, uvs: Float32Array): Float32Array {
  const result = wasm.__wbindgen_add_to_stack_pointer(-16);
  try {
    // Rust takes ownership of (and frees) the arrays passed in; views are made after each malloc, which may grow memory.
    const pass = (array: Float32Array) => {
      const pointer = wasm.__wbindgen_malloc(array.length * 4);
      new Float32Array(wasm.memory.buffer, pointer, array.length).set(array);
      return pointer;
    };
    const p = pass(positions);
    const n = pass(normals);
    const t = pass(uvs);
    wasm.generateTangents(result, p, positions.length, n, normals.length, t, uvs.length);
    const [pointer, length] = new Int32Array(wasm.memory.buffer, result, 2);
    const tangents = new Float32Array(wasm.memory.buffer, pointer, length).slice();
    wasm.__wbindgen_free(pointer, length * 4);
    return tangents;
  } finally {
    wasm.__wbindgen_add_to_stack_pointer(16);
  }
}
