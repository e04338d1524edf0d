/**
 * The benchmark's quick mode (what CI runs): one short checkpoint, no
 * Mitsuba, on three fixture scenes that take its three paths (spheres and
 * lights, a mesh, an environment map file). Checks only that it runs and
 * reports sane numbers; `npm run bench` runs every fixture scene.
 */
import { describe, expect, it } from 'vitest';
import { fixtureSceneNames, formatTable, runBench } from '../../bench/run';

describe('benchmark quick mode', () => {
  it('prints a row with finite numbers for every fixture scene', async () => {
    const scenes = ['seed', 'bunny', 'envmap'];
    for (const name of scenes) expect(fixtureSceneNames()).toContain(name);
    const result = await runBench({ scenes, times: [0.5], mitsuba: false });
    const table = formatTable(result);
    console.log(table);
    expect(result.rows.map((r) => r.scene)).toEqual(scenes);
    expect(table.split('\n')).toHaveLength(scenes.length + 2);
    for (const row of result.rows) {
      expect(row.ours.megaPathsPerSecond, row.scene).toBeGreaterThan(0);
      expect(Number.isFinite(row.ours.megaPathsPerSecond), row.scene).toBe(true);
      expect(Number.isFinite(row.ours.timeToTarget), row.scene).toBe(true);
      expect(Number.isFinite(row.startupSeconds), row.scene).toBe(true);
      for (const c of row.ours.checkpoints) {
        expect(c.spp, row.scene).toBeGreaterThan(0);
        expect(Number.isFinite(c.relMse), row.scene).toBe(true);
      }
    }
    expect(result.renderer).toMatch(/\S/);
    expect(result.machine.browser).toMatch(/\S/);
  }, 300_000);
});
