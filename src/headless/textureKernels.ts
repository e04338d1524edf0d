/**
 * A kernel of the texture lookup (src/shaders/textures/texture.glsl), for
 * test/browser/texture-lookup.test.ts: the images go through the renderer's
 * own path (decodeTextureImage, the TextureAtlas's plan and upload, the
 * texture table packScene writes), then one textureColor or textureScalar
 * per lookup, read back. Registers `window.pathtraceTextureKernels` on the
 * headless page; it ships there only, never in the library.
 */
import kernelFrag from '../shaders/test/texture_kernels.frag?raw';
import { TEXTURE_UNITS } from '../render/gl/textureUnits';
import { createDataTexture } from '../render/gl/dataTexture';
import { DATA_TEXELS, DATA_ROWS, SCENE_ROW_TEXELS } from '../render/layout/scene';
import { BASE_FEATURES, TextureTable } from '../render/packScene';
import { assembleChunks, featureDefines, sceneDefines } from '../render/shaderChunks';
import { shaderFile } from '../render/shaderSources';
import { TextureAtlas } from '../render/textures/textureAtlas';
import type { Placement } from '../render/textures/atlas';
import { decodeTextureImage } from '../scene/texture/decode';
import type { TextureImage } from '../scene/texture/image';
import type { Texture } from '../scene/texture/texture';
import { kernelContext, kernelProgram, runFullScreen } from './kernelHarness';

export interface TextureKernelRequest {
  /** Image files by name: base64 of their bytes (decoded here as the page decodes them). */
  images: Record<string, string>;
  /** The textures looked up (normalized scene-format textures) and the input each feeds. */
  textures: { texture: Texture; input: 'color' | 'scalar' }[];
  /** Per lookup: its texture (an index into `textures`) and the uv (float32). */
  lookups: { texture: number; uv: [number, number] }[];
  /** Another text of textures/texture.glsl to look up with (the test's mutants). */
  textureSource?: string;
}

export interface TextureKernelResult {
  /** base64 float32, 4 per lookup: colour RGB and 1, or the scalar and 0, 0, 1. */
  values: string;
  /** Where each of `textures` landed in the atlas. */
  placements: Placement[];
}

/** Lookups per row of the grid. */
const GRID_WIDTH = 64;

function program(formats: readonly string[], textureSource?: string) {
  const key = `test/texture_kernels.frag\n${formats.join()}\n${textureSource ?? ''}`;
  return kernelProgram(key, () => {
    const features = { ...BASE_FEATURES, textureFormats: formats as typeof BASE_FEATURES.textureFormats };
    const source = (name: string) => (name === 'textures/texture.glsl' && textureSource !== undefined ? textureSource : shaderFile(name));
    const chunks = assembleChunks(['scene/layout.glsl', 'generated/records.glsl', 'textures/texture.glsl'], source);
    return { fragment: [...chunks, { name: 'test/texture_kernels.frag', source: kernelFrag }], defines: { ...sceneDefines(), ...featureDefines(features) }, sceneBlock: true };
  });
}

export async function runTextureKernel(request: TextureKernelRequest): Promise<TextureKernelResult> {
  const images = new Map<string, TextureImage>();
  for (const [name, file] of Object.entries(request.images)) images.set(name, await decodeTextureImage(fromBase64Bytes(file)));
  // The kernel's own atlas and tables: the renderer's classes on the kernels' context.
  const gl = kernelContext();
  const atlas = new TextureAtlas(gl);
  const data = new Float32Array(DATA_TEXELS * 4);
  const lookups = new Float32Array(Math.ceil(request.lookups.length / GRID_WIDTH) * GRID_WIDTH * 4);
  let sceneData: WebGLTexture | null = null;
  let lookupTexture: WebGLTexture | null = null;
  try {
    atlas.set(request.textures.map((t) => ({ image: t.texture.image, input: t.input })), images);
    const table = new TextureTable(data, (image, input) => atlas.placement(image, input));
    const indices = request.textures.map((t) => table.index(t));
    request.lookups.forEach((l, i) => lookups.set([indices[l.texture], request.textures[l.texture].input === 'color' ? 0 : 1, ...l.uv], i * 4));
    const kernel = program([...table.formats].sort(), request.textureSource);
    const rows = lookups.length / 4 / GRID_WIDTH;
    sceneData = createDataTexture(gl, SCENE_ROW_TEXELS, DATA_ROWS, data);
    lookupTexture = createDataTexture(gl, GRID_WIDTH, rows, lookups);
    const result = runFullScreen(kernel, { uSceneData: TEXTURE_UNITS.sceneData, uLookups: TEXTURE_UNITS.kernelRays }, { uSceneData: 'int', uLookups: 'int' }, GRID_WIDTH, rows, {
      label: 'texture kernel',
      bind: (p) => {
        atlas.bind(p);
        gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNITS.sceneData);
        gl.bindTexture(gl.TEXTURE_2D, sceneData);
        gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNITS.kernelRays);
        gl.bindTexture(gl.TEXTURE_2D, lookupTexture);
        gl.activeTexture(gl.TEXTURE0);
      },
    });
    return { values: toBase64(result.subarray(0, request.lookups.length * 4)), placements: request.textures.map((t) => atlas.placement(t.texture.image, t.input)) };
  } finally {
    atlas.dispose();
    if (sceneData) gl.deleteTexture(sceneData);
    if (lookupTexture) gl.deleteTexture(lookupTexture);
  }
}

function fromBase64Bytes(text: string): Uint8Array {
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
  return bytes;
}

function toBase64(data: Float32Array): string {
  const bytes = new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
  let binary = '';
  for (let i = 0; i < bytes.length; i += 0x8000) binary += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(binary);
}

declare global {
  interface Window {
    pathtraceTextureKernels: { run: typeof runTextureKernel };
  }
}

window.pathtraceTextureKernels = { run: runTextureKernel };
