/**
 * src/node/assetTransfer.ts (decoded assets as one block for the headless
 * page) and StaticServer.publish (how the page gets the block).
 */
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { hasAssets, packAssets, unpackAssets } from '../../src/node/assetTransfer';
import { serveDirectory } from '../../src/node/server';
import { NO_ASSETS, type SceneAssets } from '../../src/scene/assets';

const assets: SceneAssets = {
  maps: new Map([['sky.exr', { width: 2, height: 1, rgb: new Float32Array([1, 2, 3, 4.5, -0, Infinity]) }]]),
  meshes: new Map([
    ['a.obj', { positions: new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]), normals: null, indices: new Uint32Array([0, 1, 2]) }],
    // A Buffer (Node's Uint8Array) and a field TriangleMesh does not have yet cross too.
    ['b.ply', { positions: new Float32Array([0.5, 0.25, 0.125]), normals: new Float32Array([0, 0, 1]), indices: new Uint32Array([0, 0, 0]), extra: { ids: Buffer.from([1, 2, 3]), count: 3 } }],
  ]),
};

describe('packAssets / unpackAssets', () => {
  it('round-trips every array, null and plain value; each array its own copy', () => {
    const { manifest, bytes } = packAssets(assets);
    expect(manifest.byteLength).toBe(bytes.byteLength);
    // The manifest is plain JSON: what crosses to the page besides the block.
    const back = unpackAssets(JSON.parse(JSON.stringify(manifest)), bytes.slice().buffer);
    expect(back).toEqual({
      maps: assets.maps,
      meshes: new Map([...assets.meshes].map(([name, mesh]) => [name, name === 'b.ply' ? { ...mesh, extra: { ids: new Uint8Array([1, 2, 3]), count: 3 } } : mesh])),
      images: new Map(),
    });
    const a = back.meshes.get('a.obj')!;
    expect(a.positions).toBeInstanceOf(Float32Array);
    expect(a.indices).toBeInstanceOf(Uint32Array);
    expect(a.positions.buffer).not.toBe(a.indices.buffer);
    expect(Object.is(back.maps.get('sky.exr')!.rgb[4], -0)).toBe(true);
  });

  it('refuses a block of the wrong size; knows when there is nothing to send', () => {
    const { manifest, bytes } = packAssets(assets);
    expect(() => unpackAssets(manifest, bytes.slice(0, 8).buffer)).toThrow(/bytes, expected/);
    expect(hasAssets(undefined)).toBe(false);
    expect(hasAssets(NO_ASSETS)).toBe(false);
    expect(hasAssets(assets)).toBe(true);
  });
});

describe('StaticServer.publish', () => {
  it('serves the bytes once, then 404; the page files are served as before', async () => {
    const root = mkdtempSync(join(tmpdir(), 'pathtrace-serve-'));
    const server = await serveDirectory(root);
    try {
      const path = server.publish(new Uint8Array([9, 8, 7]));
      const first = await fetch(`${server.url}${path}`);
      expect(first.status).toBe(200);
      expect(Array.from(new Uint8Array(await first.arrayBuffer()))).toEqual([9, 8, 7]);
      expect((await fetch(`${server.url}${path}`)).status).toBe(404);
      expect(server.publish(new Uint8Array(1))).not.toBe(path);
      expect((await fetch(`${server.url}missing.html`)).status).toBe(404);
    } finally {
      await server.close();
      rmSync(root, { recursive: true, force: true });
    }
  });
});
