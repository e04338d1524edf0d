/**
 * The text of every file under src/shaders/ and of the material kinds'
 * GLSL under src/materials/, bundled by Vite, and the
 * chunk lists of the programs built from it (see shaderChunks.ts).
 */
import type { ShaderChunk } from './gl/shaderSource';
import { assembleChunks, SCENE_CHUNK_NAMES, TRACE_CHUNK_NAMES } from './shaderChunks';

const FILES = {
  ...import.meta.glob('../shaders/**/*.{glsl,frag,vert}', { query: '?raw', import: 'default', eager: true }),
  ...import.meta.glob('../materials/**/*.glsl', { query: '?raw', import: 'default', eager: true }),
  ...import.meta.glob('../lights/**/*.glsl', { query: '?raw', import: 'default', eager: true }),
} as Record<string, string>;

/** The text of src/shaders/NAME (a material kind's chunk: ../materials/KIND/FILE). */
export function shaderFile(name: string): string {
  const path = name.startsWith('../materials/') || name.startsWith('../lights/') ? name : `../shaders/${name}`;
  const text = FILES[path];
  if (text === undefined) throw new Error(`no shader file src/shaders/${name}`);
  return text;
}

export const VERTEX_CHUNKS: ShaderChunk[] = assembleChunks(['fullscreen.vert'], shaderFile);
export const SCENE_CHUNKS: ShaderChunk[] = assembleChunks(SCENE_CHUNK_NAMES, shaderFile);
export const TRACE_CHUNKS: ShaderChunk[] = assembleChunks(TRACE_CHUNK_NAMES, shaderFile);
