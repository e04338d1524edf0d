/**
 * The mesh decoders in the browser (the page's bundle) give exactly what they
 * give in Node, and the same errors. Draco's decoder is WebAssembly: it runs
 * only where the page's Content-Security-Policy allows 'wasm-unsafe-eval';
 * elsewhere a Draco file gives a clear AssetError.
 */
import { readFileSync, readdirSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { decodeMesh } from '../../src/scene/mesh';
import { useRenderSession } from '../support/browser';

const FIXTURES = new URL('../fixtures/meshes/', import.meta.url);
const b64 = (a: ArrayBufferView) => Buffer.from(a.buffer, a.byteOffset, a.byteLength).toString('base64');

describe('mesh decoders in the browser', () => {
  const session = useRenderSession();
  const decode = (name: string, bytes: Uint8Array) => session().page.evaluate(([n, b]) => window.pathtraceBvh.decodeInPage(n, b), [name, b64(bytes)] as const);

  const files = readdirSync(FIXTURES).filter((f) => /\.(obj|ply|gltf|glb)$/.test(f));
  it(`every fixture decodes as in Node (${files.length} files, Draco included)`, async () => {
    expect(files.filter((f) => f.includes('draco')).length).toBe(2);
    const csp = await session().page.evaluate(() => document.querySelector('meta[http-equiv="Content-Security-Policy"]')?.getAttribute('content') ?? '');
    const wasmAllowed = !csp || csp.includes("'wasm-unsafe-eval'");
    for (const file of files) {
      const bytes = new Uint8Array(readFileSync(new URL(file, FIXTURES)));
      const expected = await decodeMesh(bytes, file);
      const actual = await decode(file, bytes);
      if (file.includes('draco') && !wasmAllowed) {
        expect(actual, file).toEqual({ error: expect.stringMatching(/^AssetError: the file is Draco-compressed and the Draco decoder \(WebAssembly\) cannot run here \(.*Content Security.*\): convert it to an uncompressed glTF first, e\.g\. `npx @gltf-transform\/cli copy in\.glb out\.glb`/) });
        continue;
      }
      expect(actual, file).toEqual({
        positions: b64(expected.positions),
        normals: expected.normals ? b64(expected.normals) : null,
        indices: b64(expected.indices),
        uvs: expected.uvs ? b64(expected.uvs) : null,
        uvs1: expected.uvs1 ? b64(expected.uvs1) : null,
      });
    }
  });

  it('a bad file gives the same AssetError', async () => {
    const bytes = new TextEncoder().encode('v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 5\n');
    expect(await decode('bad.obj', bytes)).toEqual({ error: 'AssetError: line 4: vertex index 5 is out of range (3 defined so far)' });
  });
});
