/**
 * Textures as scene input (scene format version 3, "Textures"): what the
 * schema refuses, and what loading a scene's images refuses, each naming
 * the key (a texture on a sphere, channel "x", a missing, corrupt or
 * oversized image, KTX2, a normal map on a mesh without coordinates, more
 * decoded texture memory than the limit).
 */
import { deflateSync } from 'node:zlib';
import { describe, expect, it } from 'vitest';
import { loadSceneAssets } from '../../src/scene/assets';
import { SceneError, safeParseScene, type SceneIssue } from '../../src/scene/schema';
import type { TextureImage } from '../../src/scene/texture/image';
import { MAX_TEXTURE_BYTES } from '../../src/scene/texture/limits';
import type { Scene } from '../../src/scene/types';

const camera = { position: [0, 1, 5], target: [0, 0, 0] };
const textured = (extra: Record<string, unknown> = {}) => ({ type: 'principled', baseColor: { image: 'c.png' }, ...extra });

function issuesOf(json: unknown): SceneIssue[] {
  const r = safeParseScene(json);
  return r.ok ? [] : r.issues;
}

/** A valid 8-bit RGBA PNG of w x h texels. */
function png(w: number, h: number): Uint8Array {
  const crcTable = Array.from({ length: 256 }, (_, n) => {
    let c = n;
    for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    return c >>> 0;
  });
  const crc = (b: Uint8Array) => {
    let c = 0xffffffff;
    for (const x of b) c = crcTable[(c ^ x) & 255] ^ (c >>> 8);
    return (c ^ 0xffffffff) >>> 0;
  };
  const chunk = (type: string, data: Uint8Array) => {
    const out = new Uint8Array(12 + data.length);
    const view = new DataView(out.buffer);
    view.setUint32(0, data.length);
    out.set(new TextEncoder().encode(type), 4);
    out.set(data, 8);
    view.setUint32(8 + data.length, crc(out.subarray(4, 8 + data.length)));
    return out;
  };
  const ihdr = new Uint8Array(13);
  new DataView(ihdr.buffer).setUint32(0, w);
  new DataView(ihdr.buffer).setUint32(4, h);
  ihdr.set([8, 6, 0, 0, 0], 8);
  const raw = new Uint8Array(h * (1 + w * 4)).map((_, i) => (i % (1 + w * 4) === 0 ? 0 : i & 255));
  const parts = [new Uint8Array([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', ihdr), chunk('IDAT', deflateSync(raw)), chunk('IEND', new Uint8Array())];
  const out = new Uint8Array(parts.reduce((n, p) => n + p.length, 0));
  let at = 0;
  for (const p of parts) (out.set(p, at), (at += p.length));
  return out;
}

const quadObj = (withUvs: boolean) =>
  new TextEncoder().encode(
    withUvs
      ? 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n'
      : 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n',
  );

async function loadIssues(scene: Scene, files: Record<string, Uint8Array>, decode?: (b: Uint8Array) => Promise<TextureImage>): Promise<SceneIssue[]> {
  try {
    await loadSceneAssets(scene, async (name) => {
      const f = files[name];
      if (!f) throw new Error('ENOENT: no such file');
      return f;
    }, undefined, decode);
    return [];
  } catch (error) {
    if (error instanceof SceneError) return error.issues;
    throw error;
  }
}

const parse = (json: unknown): Scene => {
  const r = safeParseScene(json);
  if (!r.ok) throw new Error(JSON.stringify(r.issues));
  return r.scene;
};

describe('textures in the schema', () => {
  it('refuses a texture on a sphere, naming the input', () => {
    expect(issuesOf({ version: 3, camera, spheres: [{ center: [0, 0, 0], radius: 1, material: textured() }] })).toEqual([
      { path: 'spheres[0].material.baseColor', message: 'cannot be a texture on a sphere (spheres have no texture coordinates)' },
    ]);
  });

  it('refuses channel "x" and a version-2 document, naming the key', () => {
    const issues = issuesOf({ version: 3, camera, ground: { material: { type: 'principled', roughness: { image: 'r.png', channel: 'x' } } } });
    expect(issues.map((i) => i.path)).toEqual(['ground.material.roughness.channel']);
    expect(issuesOf({ version: 2, camera, ground: { material: textured() } }).length).toBeGreaterThan(0);
  });

  it('refuses a transmitting principled ground (a plane has no inside)', () => {
    expect(issuesOf({ version: 3, camera, ground: { material: { type: 'principled', specTrans: { image: 't.png' } } } }).map((i) => i.path)).toEqual(['ground.material.type']);
  });

  it('round-trips textures with every default explicit', async () => {
    const { serializeScene } = await import('../../src/scene/serialize');
    const scene = parse({ version: 3, camera, ground: { material: textured({ roughness: { image: 'r.png', channel: 'g', scale: 0.8, uv: { rotation: 20 } }, opacity: { image: 'a.png', channel: 'a', cutoff: 0.5 } }) } });
    expect(parse(serializeScene(scene))).toEqual(scene);
  });
});

describe("loading a scene's images", () => {
  const groundScene = (material: Record<string, unknown>) => parse({ version: 3, camera, ground: { material } });

  it('decodes each image once and reports a missing one at its key', async () => {
    const scene = groundScene(textured({ roughness: { image: 'missing.png' } }));
    const issues = await loadIssues(scene, { 'c.png': png(2, 2) });
    expect(issues).toHaveLength(1);
    expect(issues[0].path).toBe('ground.material.roughness.image');
    expect(issues[0].message).toMatch(/^"missing.png": /);
  });

  it('refuses a corrupt PNG, a truncated one, a 100000 x 100000 header and a KTX2 image, each at its key', async () => {
    const good = png(4, 4);
    const corrupt = good.slice();
    corrupt[good.length - 20] ^= 0xff;
    const huge = png(1, 1);
    new DataView(huge.buffer).setUint32(16, 100000);
    new DataView(huge.buffer).setUint32(20, 100000);
    const ktx2 = new Uint8Array([0xab, 0x4b, 0x54, 0x58, 0x20, 0x32, 0x30, 0xbb, 0x0d, 0x0a, 0x1a, 0x0a, 0, 0, 0, 0]);
    const scene = groundScene({
      type: 'principled',
      baseColor: { image: 'corrupt.png' },
      metallic: { image: 'truncated.png' },
      roughness: { image: 'huge.png' },
      clearcoat: { image: 'k.ktx2' },
    });
    const issues = await loadIssues(scene, { 'corrupt.png': corrupt, 'truncated.png': good.subarray(0, 40), 'huge.png': huge, 'k.ktx2': ktx2 });
    expect(issues.map((i) => i.path)).toEqual(['ground.material.baseColor.image', 'ground.material.metallic.image', 'ground.material.roughness.image', 'ground.material.clearcoat.image']);
    expect(issues[2].message).toMatch(/100000/);
    expect(issues[3].message).toMatch(/KTX2/);
  });

  it('refuses a normal map on a mesh whose file has no texture coordinates, naming the file', async () => {
    const scene = parse({ version: 3, camera, meshes: [{ file: 'flat.obj', material: { type: 'principled', normalMap: { image: 'n.png' } } }] });
    const issues = await loadIssues(scene, { 'flat.obj': quadObj(false), 'n.png': png(2, 2) });
    expect(issues).toEqual([{ path: 'meshes[0].file', message: expect.stringMatching(/"flat.obj" has no texture coordinates/) }]);
    expect(await loadIssues(scene, { 'flat.obj': quadObj(true), 'n.png': png(2, 2) })).toEqual([]);
  });

  it('refuses more decoded texture memory than the limit, at the image that crosses it', async () => {
    const side = 4096; // 256 MB each as float: the third crosses 512 MB
    const big = (): Promise<TextureImage> => Promise.resolve({ width: side, height: side, format: 'png', encoding: 'f32', data: new Float32Array(4) });
    const scene = groundScene(textured({ roughness: { image: 'r.png' }, metallic: { image: 'm.png' } }));
    expect(2 * side * side * 16).toBe(MAX_TEXTURE_BYTES);
    const issues = await loadIssues(scene, { 'c.png': png(1, 1), 'r.png': png(1, 1), 'm.png': png(1, 1) }, big);
    expect(issues).toEqual([{ path: 'ground.material.roughness.image', message: expect.stringMatching(/more than 512 MB decoded/) }]);
  });
});
