/**
 * A kernel that traces rays through the GLSL BVH traversal (bvh.glsl), for
 * the browser tests: `window.pathtraceBvh.trace(request)`. Ships in the
 * headless page only.
 */
import bvhGlsl from '../shaders/scene/bvh.glsl?raw';
import kernelFrag from '../shaders/test/bvh_kernels.frag?raw';
import { TEXTURE_UNITS } from '../render/gl/textureUnits';
import { BvhTextures, bvhDefines } from '../render/bvhTextures';
import { createDataTextureArray } from '../render/gl/dataTexture';
import { BVH_ROOT_NODE, bvhTexture, type LayeredTextureData, type PackedBvh } from '../render/bvh/pack';
import { buildBvhAsync } from '../render/bvh/buildAsync';
import { decodeMesh } from '../scene/mesh';
import { kernelProgram, runFullScreen } from './kernelHarness';

export interface BvhTraceRequest {
  /** base64 of the packed texture data; empty = the BVH last built by buildInWorker (large meshes). */
  texture: string;
  /** base64 Float32Array, 8 floats per ray: origin, tMax, direction, 0. */
  rays: string;
  /** Rays per row of the output (width); rays.length / 8 / width rows. */
  width: number;
  mode: 'closest' | 'any' | 'surface' | 'uv';
  /** Mode 'uv': the root node of the group to traverse (default the first group's, BVH_ROOT_NODE; packed.roots). */
  root?: number;
  /** Extra timed draws after the first (for bench/bvh-trace.ts): then the result is their mean time in ms, as text. */
  timedDraws?: number;
  /** Another text of scene/bvh.glsl to trace with (bench/bvh-kernel-ab.ts compares variants). */
  bvhSource?: string;
}

const MODES = { closest: 0, any: 1, surface: 2, uv: 3 } as const;

function fromBase64(text: string): Float32Array {
  return new Float32Array(fromBase64Bytes(text).buffer);
}

function toBase64(data: Float32Array): string {
  const bytes = new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
  let binary = '';
  for (let i = 0; i < bytes.length; i += 0x8000) binary += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(binary);
}

let lastBuilt: PackedBvh | null = null;

/** Texel data (base64) in the BVH textures' layout, padded as packBvh pads it. */
function asTexture(base64: string): LayeredTextureData {
  const data = fromBase64(base64);
  const texture = bvhTexture(data.length / 4);
  texture.data.set(data);
  return texture;
}

/** The kernel program for a text of bvh.glsl (default: the built one). */
function bvhProgram(source = bvhGlsl) {
  return kernelProgram(`test/bvh_kernels.frag\n${source}`, () => ({
    fragment: [{ name: 'scene/bvh.glsl', source }, { name: 'test/bvh_kernels.frag', source: kernelFrag }],
    // bvh.glsl alone: its switches besides HAS_MESHES off (normal maps' derivatives, instances).
    defines: { ...bvhDefines(), HAS_MESHES: 1, HAS_NORMAL_MAPS: 0 },
  }));
}

/** Traces the request's rays; returns RGBA float32 per ray (closest: triangle, t, b1, b2; any: hit; surface: shading normal, material; uv: u, v, triangle, t). */
export function traceBvh(request: BvhTraceRequest): string {
  const kernel = bvhProgram(request.bvhSource);
  const { gl } = kernel;
  const packed = request.texture === '' && lastBuilt ? lastBuilt : ({ texture: asTexture(request.texture) } as PackedBvh);
  const rayCount = fromBase64(request.rays).length / 8;
  const rows = Math.ceil(rayCount / request.width);
  const textures = new BvhTextures(gl, packed);
  const rayData = asTexture(request.rays);
  const rays = createDataTextureArray(gl, rayData.width, rayData.height, rayData.layers, rayData.data);
  try {
    const result = runFullScreen(
      kernel,
      { uRays: TEXTURE_UNITS.kernelRays, uMode: MODES[request.mode], uGridWidth: request.width, uRoot: request.root ?? BVH_ROOT_NODE },
      { uRays: 'int', uMode: 'int', uGridWidth: 'int', uRoot: 'int' },
      request.width,
      rows,
      {
        label: 'bvh kernel',
        bind: (program) => {
          textures.bind(program, TEXTURE_UNITS.bvh);
          gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNITS.kernelRays);
          gl.bindTexture(gl.TEXTURE_2D_ARRAY, rays);
        },
        timedDraws: request.timedDraws,
      },
    );
    return typeof result === 'number' ? String(result) : toBase64(result.subarray(0, rayCount * 4));
  } finally {
    textures.dispose();
    gl.deleteTexture(rays);
  }
}

/** Builds a BVH in the page's worker over one mesh (base64 Float32 positions, normals or null, Uint32 indices, Float32 uvs or null); returns the packed texture (base64). */
export async function buildInWorker(positions: string, normals: string | null, indices: string, material: number, summaryOnly = false, uvs: string | null = null): Promise<{ texture: string; depth: number; milliseconds: number }> {
  const start = performance.now();
  const index = fromBase64(indices);
  const mesh = { positions: fromBase64(positions), normals: normals === null ? null : fromBase64(normals), indices: new Uint32Array(index.buffer), uvs: uvs === null ? null : fromBase64(uvs), material };
  const packed = await buildBvhAsync([[mesh]]);
  lastBuilt = packed;
  const milliseconds = performance.now() - start;
  if (summaryOnly) return { texture: '', depth: packed.depth, milliseconds };
  return { texture: toBase64(packed.texture.data), depth: packed.depth, milliseconds };
}

/** Decodes a mesh file in the page (base64 bytes); returns its arrays as base64 (uvs, uvs1: null when absent), or the AssetError's message. */
export async function decodeInPage(fileName: string, bytes: string): Promise<{ positions: string; normals: string | null; indices: string; uvs: string | null; uvs1: string | null } | { error: string }> {
  const raw = fromBase64Bytes(bytes);
  try {
    const mesh = await decodeMesh(raw, fileName);
    const optional = (a: Float32Array | null | undefined) => (a ? toBase64(a) : null);
    return { positions: toBase64(mesh.positions), normals: optional(mesh.normals), indices: toBase64(new Float32Array(mesh.indices.buffer)), uvs: optional(mesh.uvs), uvs1: optional(mesh.uvs1) };
  } catch (error) {
    return { error: `${(error as Error).name}: ${(error as Error).message}` };
  }
}

function fromBase64Bytes(text: string): Uint8Array {
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
  return bytes;
}

declare global {
  interface Window {
    pathtraceBvh: { trace: typeof traceBvh; buildInWorker: typeof buildInWorker; decodeInPage: typeof decodeInPage };
  }
}

window.pathtraceBvh = { trace: traceBvh, buildInWorker, decodeInPage };
