/**
 * The page's bundled environment maps and how scenes name them: every
 * bundled map decodes with the project's decoder (DWAB) to finite texels,
 * names round-trip, a scene naming a bundled map resolves without any file
 * (what a share link needs), a file opened with the scene wins over the
 * bundle, a missing user map is an issue at environment.map, and the page's
 * map example is a valid scene naming a bundled map. (In Node there is no
 * Worker: the page's decoder decodes in place, the same code.)
 */
import { describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import { BUNDLED_MAP_NAMES, bundledMapBytes, bundledMapFile, bundledMapName } from '../../src/app/bundledMaps';
import { MAP_EXAMPLES } from '../../src/app/examples';
import { resolveAssets } from '../../src/app/sceneLoader';
import { decodeEnvironmentMap } from '../../src/scene/envmap';
import { defaultScene } from '../../src/scene/presets';
import { safeParseScene } from '../../src/scene/schema';
import type { Scene } from '../../src/scene/types';

/** A mesh entry with the format's defaults (the file is set by the test). */
const parseMesh = () => {
  const result = safeParseScene({ version: 2, camera: { position: [0, 0, 5], target: [0, 0, 0] }, meshes: [{ file: 'x.obj' }] });
  if (!result.ok) throw new Error('mesh defaults');
  return result.scene.meshes[0];
};
const withMap = (map: string): Scene => ({ ...defaultScene(), version: 2, environment: { map, intensity: 1, rotation: 0 } });

describe('bundled environment maps', () => {
  it('each decodes with our decoder: 512x256 DWAB, finite, not black', async () => {
    expect(BUNDLED_MAP_NAMES.length).toBeGreaterThanOrEqual(3);
    for (const name of BUNDLED_MAP_NAMES) {
      const bytes = await bundledMapBytes(name);
      expect(bytes[0], `${name}: OpenEXR magic`).toBe(0x76);
      const image = decodeEnvironmentMap(bytes, bundledMapFile(name));
      expect([image.width, image.height], name).toEqual([512, 256]);
      let sum = 0;
      let nonFinite = 0;
      for (const v of image.rgb) {
        if (Number.isFinite(v)) sum += v;
        else nonFinite++;
      }
      expect(nonFinite, name).toBe(0);
      expect(sum / image.rgb.length, `${name}: mean radiance`).toBeGreaterThan(0.01);
    }
  });

  it('names round-trip; other names are not bundled', () => {
    for (const name of BUNDLED_MAP_NAMES) expect(bundledMapName(bundledMapFile(name))).toBe(name);
    for (const other of ['studio.exr', 'bundled/studio.hdr', 'bundled/nothing.exr', 'bundled/constructor.exr', 'x/bundled/studio.exr']) {
      expect(bundledMapName(other), other).toBeNull();
    }
  });

  it('a scene naming a bundled map resolves without files; an opened file wins; a missing user map is rejected at environment.map', async () => {
    const bundled = await resolveAssets(withMap('bundled/studio.exr'), new Map());
    expect(bundled.ok && bundled.assets.maps.get('bundled/studio.exr')?.width).toBe(512);

    const own = readFileSync(new URL('../fixtures/envmaps/gradient-rle.hdr', import.meta.url));
    const opened = await resolveAssets(withMap('bundled/studio.exr'), new Map([['studio.exr', new Blob([own])]]));
    const gradient = decodeEnvironmentMap(own, 'gradient-rle.hdr');
    expect(opened.ok && opened.assets.maps.get('bundled/studio.exr')?.width).toBe(gradient.width);

    const missing = await resolveAssets(withMap('sky.hdr'), new Map());
    expect(missing.ok).toBe(false);
    if (!missing.ok) expect(missing.issues).toEqual([{ path: 'environment.map', message: expect.stringMatching(/^"sky\.hdr": not opened/) }]);

    // Every unusable file is reported, not only the map.
    const both = await resolveAssets({ ...withMap('sky.hdr'), meshes: [{ ...parseMesh(), file: 'gem.obj' }] }, new Map());
    expect(both.ok ? [] : both.issues.map((i) => i.path)).toEqual(['environment.map', 'meshes[0].file']);

    const broken = await resolveAssets(withMap('sky.hdr'), new Map([['sky.hdr', new Blob([own.subarray(0, 40)])]]));
    expect(broken.ok).toBe(false);
    if (!broken.ok) expect(broken.issues[0].path).toBe('environment.map');
  });

  it('the map examples are valid scenes naming bundled maps', () => {
    for (const [name, data] of Object.entries(MAP_EXAMPLES)) {
      const result = safeParseScene(data);
      expect(result.ok, name).toBe(true);
      const env = result.ok ? result.scene.environment : null;
      expect(env && 'map' in env && bundledMapName(env.map), name).toBeTruthy();
    }
  });
});
