/**
 * The page's "+ Light" offers every light kind (the registry's), adds the
 * chosen one to the scene (which saves as version 3 once it has a kind of
 * version 3) and keeps rendering; the selected light's panel shows its
 * kind's controls, and editing one changes the saved scene.
 */
import { describe, expect, it } from 'vitest';
import { LIGHT_TYPE_NAMES } from '../../src/lights/registry';
import { openPage, savedScene, usePageHarness, waitForSpp } from '../support/page';

const harness = usePageHarness();

describe('page: studio lights', () => {
  it('"+ Light" adds each kind, and the panel edits the selected one', async () => {
    const { page, errors } = await openPage(harness());
    const options = await page.locator('#light-kind option').evaluateAll((os) => os.map((o) => (o as HTMLOptionElement).value));
    expect(options).toEqual([...LIGHT_TYPE_NAMES]);
    const before = ((await savedScene(page)).lights as unknown[]).length;
    for (const type of ['spot', 'rectangle']) {
      await page.selectOption('#light-kind', type);
      await page.click('#add-light');
    }
    await waitForSpp(page, 2);
    // The last added light (the rectangle) is selected: its controls include the size.
    const selection = page.locator('.lil-root > .lil-children > .lil-gui').first();
    await expect.poll(() => selection.locator('.lil-name', { hasText: /^size x$/ }).count()).toBe(1);
    const intensity = selection.locator('.lil-controller', { has: page.locator('.lil-name', { hasText: /^intensity$/ }) }).locator('input').first();
    await intensity.fill('7');
    await intensity.press('Enter');
    const scene = await savedScene(page);
    expect(scene.version).toBe(3);
    const lights = scene.lights as { type: string; intensity: number }[];
    expect(lights.length).toBe(before + 2);
    expect(lights.slice(-2).map((l) => l.type)).toEqual(['spot', 'rectangle']);
    expect(lights[lights.length - 1].intensity).toBe(7);
    await waitForSpp(page, 2);
    expect(errors).toEqual([]);
    await page.close();
  }, 300_000);
});
