/**
 * A model's files beside it on the page (companionFiles.ts, userFiles.ts):
 * a .gltf's .bin and images are found among the files dropped with it, by
 * the names it uses relative to it; a file over the page's limit is refused
 * from its size, unread; the autosave keeps the .bin and the images with the
 * .gltf and decodes them all again at start; the share link's list names
 * them. The store is an in-memory stub; the image Worker is the Node decoder.
 */
import { afterEach, beforeEach, describe, expect, it, vi } from 'vitest';
import { History } from '../../src/app/history';
import { parseScene } from '../../src/scene/schema';
import type { Scene } from '../../src/scene/types';
import { quadsGltf } from '../support/gltfQuads';

vi.mock('../../src/app/store', () => import('../support/memoryStore'));
const { stored } = await import('../support/memoryStore');
vi.mock('../../src/render/images/decodeImages', () => import('../support/nodeImageDecoder'));

const { Autosave, readStartState } = await import('../../src/app/persistence');
const { resolveAssets } = await import('../../src/app/sceneLoader');
const { companionResolver, readUserFile } = await import('../../src/app/companionFiles');
const { userFiles } = await import('../../src/app/userFiles');
const { MAX_ASSET_BYTES } = await import('../../src/app/fileLimits');

const blobs = (files: Record<string, Uint8Array>) => new Map(Object.entries(files).map(([name, bytes]) => [name, new Blob([bytes as BlobPart])] as const));
const quadsScene = (): Scene => parseScene({
  version: 3,
  camera: { position: [0, 0, 4], target: [0, 0, 0], fov: 40 },
  image: { width: 32, height: 32 },
  environment: { color: [1, 1, 1], intensity: 1 },
  spheres: [],
  meshes: [{ file: 'quads.gltf' }],
});

describe("a model's files beside it", () => {
  it('reads them by the name the model uses, relative to it, else by base name, and lists those read', async () => {
    const files = blobs({ 'a.bin': new Uint8Array([1, 2]), 'my tex.png': new Uint8Array([3]) });
    const companions = companionResolver(files, 'models/car.gltf');
    expect([...(await companions.resolve('a.bin'))]).toEqual([1, 2]); // models/a.bin: dropped without its folder
    expect([...(await companions.resolve('../textures/my%20tex.png'))]).toEqual([3]);
    expect(companions.read).toEqual(['a.bin', 'my tex.png']);
    await expect(companions.resolve('b.bin')).rejects.toThrow('"models/b.bin" was not opened with it');
    expect(companions.read).toEqual(['a.bin', 'my tex.png']);
  });

  it('refuses a file over the limit from its size, without reading it', async () => {
    const huge = { size: MAX_ASSET_BYTES + 1, arrayBuffer: () => Promise.reject(new Error('read')) } as unknown as Blob;
    await expect(readUserFile(huge)).rejects.toThrow(`the file is ${MAX_ASSET_BYTES + 1} bytes; the page takes files of at most 64 MB`);
  });

  it('names a missing .bin at the mesh that needs it', async () => {
    const { 'quads.bin': _bin, ...rest } = await quadsGltf();
    const result = await resolveAssets(quadsScene(), blobs(rest));
    expect(result.ok).toBe(false);
    if (!result.ok) expect(result.issues).toEqual([{ path: 'meshes[0].file', message: '"quads.gltf": its buffer "quads.bin": not opened: open or drop it together with the scene or model that names it' }]);
  });
});

describe('a .gltf in the autosave', () => {
  beforeEach(() => {
    vi.stubGlobal('window', globalThis);
    stored.clear();
  });
  afterEach(() => vi.unstubAllGlobals());

  it('keeps the .bin and the images with the .gltf, names them for the link, and decodes them again at start', async () => {
    const scene = quadsScene();
    const files = blobs({ ...(await quadsGltf()), 'unrelated.png': new Uint8Array([1]) });
    const loaded = await resolveAssets(scene, files);
    if (!loaded.ok) throw new Error(JSON.stringify(loaded.issues));
    expect(userFiles(scene, loaded.assets).sort()).toEqual(['blue.png', 'quads.bin', 'quads.gltf', 'red.png']);
    const app = { scene, assets: loaded.assets, homeView: scene.camera, view: { exposure: 0, toneMap: 'aces', paused: false, targetSpp: 0, denoise: false }, history: new History<Scene>() };
    const autosave = new Autosave(app as never, () => {}, 0);
    await autosave.keepFiles(scene, files);
    await autosave.flush();
    expect([...stored.keys()].sort()).toEqual(['asset:blue.png', 'asset:quads.bin', 'asset:quads.gltf', 'asset:red.png', 'autosave']);

    const start = await readStartState('');
    expect(start.notices.join(' ')).not.toMatch(/discarded/);
    expect(start.saved?.scene.meshes[0].material).toBeNull();
    expect(start.assets.meshes.get('quads.gltf')?.fileMaterials?.materials.map((m) => m.name)).toEqual(expect.arrayContaining(['left', 'right']));
    expect([...(start.assets.images?.keys() ?? [])].sort()).toEqual(['blue.png', 'red.png']);
    expect(userFiles(start.saved!.scene, start.assets).sort()).toEqual(['blue.png', 'quads.bin', 'quads.gltf', 'red.png']);
  });

  it('leaves bundled maps out of the user files', () => {
    const scene = parseScene({ ...quadsScene(), meshes: [], environment: { map: 'bundled/studio.exr' } });
    expect(userFiles(scene, { maps: new Map(), meshes: new Map() })).toEqual([]);
  });
});
