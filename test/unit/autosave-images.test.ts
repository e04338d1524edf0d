/**
 * Texture images are autosaved with the scene (kept as the user's files in
 * the page's store, like maps and models) and come back decoded at start.
 * The store is an in-memory stub here; the image Worker is the Node decoder.
 */
import { readFileSync } from 'node:fs';
import { afterEach, beforeEach, describe, expect, it, vi } from 'vitest';
import { TEXTURE_EXAMPLES } from '../../src/app/examples';
import { History } from '../../src/app/history';
import { parseScene } from '../../src/scene/schema';
import { serializeScene } from '../../src/scene/serialize';
import type { Scene } from '../../src/scene/types';
import { NO_ASSETS } from '../../src/scene/assets';

vi.mock('../../src/app/store', () => import('../support/memoryStore'));
const { stored } = await import('../support/memoryStore');
vi.mock('../../src/render/images/decodeImages', () => import('../support/nodeImageDecoder'));

const { Autosave, readStartState } = await import('../../src/app/persistence');

const fixture = (path: string) => new Blob([readFileSync(new URL(`../fixtures/${path}`, import.meta.url))]);

describe('texture images in the autosave', () => {
  beforeEach(() => {
    vi.stubGlobal('window', globalThis);
    stored.clear();
  });
  afterEach(() => vi.unstubAllGlobals());

  it('keeps the images a scene names and decodes them again at start', async () => {
    // The textured example, lit by a constant (the bundled map is the page's).
    const scene: Scene = parseScene({ ...(TEXTURE_EXAMPLES.textured.scene as object), environment: { color: [1, 1, 1], intensity: 0.5 } });
    const app = { scene, assets: NO_ASSETS, homeView: scene.camera, view: { exposure: 0, toneMap: 'aces', paused: false, targetSpp: 0, denoise: false }, history: new History<Scene>() };
    const autosave = new Autosave(app as never, () => {}, 0);
    const files = new Map([
      ['checker.png', fixture('textures/checker.png')],
      ['grid.png', fixture('textures/grid.png')],
      ['rough.png', fixture('textures/rough.png')],
      ['bumps.png', fixture('textures/bumps.png')],
      ['uvbox.obj', fixture('meshes/uvbox.obj')],
    ]);
    await autosave.keepFiles(scene, files);
    await autosave.flush();
    expect([...stored.keys()].sort()).toEqual(['asset:bumps.png', 'asset:checker.png', 'asset:grid.png', 'asset:rough.png', 'asset:uvbox.obj', 'autosave']);
    expect(autosave.unsaved.size).toBe(0);

    const start = await readStartState('');
    expect(start.notices.join(' ')).not.toMatch(/discarded/);
    expect(start.saved && serializeScene(start.saved.scene)).toEqual(serializeScene(scene));
    const sizes = Object.fromEntries([...(start.assets.images ?? new Map())].map(([name, image]) => [name, `${image.width}x${image.height}`]));
    expect(sizes).toEqual({ 'checker.png': '256x256', 'rough.png': '128x128', 'grid.png': '128x128', 'bumps.png': '128x128' });
  });

  it('discards a saved scene whose image is no longer kept, naming it', async () => {
    const scene: Scene = parseScene({ ...(TEXTURE_EXAMPLES.textured.scene as object), environment: null });
    const app = { scene, assets: NO_ASSETS, homeView: scene.camera, view: { exposure: 0, toneMap: 'aces', paused: false, targetSpp: 0, denoise: false }, history: new History<Scene>() };
    const autosave = new Autosave(app as never, () => {}, 0);
    await autosave.keepFiles(scene, new Map([['uvbox.obj', fixture('meshes/uvbox.obj')], ['grid.png', fixture('textures/grid.png')]]));
    await autosave.flush();
    const start = await readStartState('');
    expect(start.saved).toBeNull();
    expect(start.notices.join(' ')).toMatch(/ground\.material\.baseColor\.image: "checker\.png": not opened/);
  });
});
