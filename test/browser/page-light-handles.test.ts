/**
 * The selected light's handles on the page (src/app/lightHandles.ts): a
 * spot's move handle drags it in the plane facing the camera, its aim
 * handle puts its target on the ground under the cursor, a directional
 * light's handle turns it; each drag is one undo step, restarts the
 * accumulation, never links a program, and reaches the autosave; a drag
 * away from the handles still orbits; a rectangle's aim handle turns it to
 * face the ground under the cursor; Escape during a drag cancels it (the
 * light turns back, no undo step), else deselects; a deselected directional
 * light's sun marker selects it on a click and turns it on a drag, never
 * orbiting; the panel's object list and the markers select a light by
 * keyboard as a click does. A scene of spheres with one spot, one
 * rectangle and one directional light, rendered at 160 pixels.
 */
import type { Page } from 'playwright-core';
import { describe, expect, it } from 'vitest';
import { shareHash } from '../../src/app/files';
import { draggedLight, emitDirection, handlePoints } from '../../src/app/lightHandles';
import type { Light } from '../../src/lights/registry';
import { cameraRay } from '../../src/scene/camera';
import { projectPoint } from '../../src/scene/picking';
import { parseScene } from '../../src/scene/schema';
import type { Camera, Vec3 } from '../../src/scene/types';
import { canvasPoint, drag, instrument, openPage, probe, savedScene, usePageHarness, waitForRestart, waitForSpp, watchRestarts } from '../support/page';

const harness = usePageHarness();

const SPOT = { type: 'spot', position: [1.5, 3, 1.5], target: [0, 0.5, 0], color: [1, 1, 1], intensity: 30, cutoffAngle: 30, beamWidth: 20 };
const PANEL = { type: 'rectangle', position: [-1.8, 2.4, 1.2], rotation: [0, 0, 0], size: [0.5, 0.5], color: [1, 1, 1], intensity: 4 };
const SUN = { type: 'directional', direction: [0.4, -1, -0.2], color: [1, 1, 1], irradiance: 0.5 };
const scene = parseScene({
  version: 3,
  camera: { position: [0, 2.2, 7.5], target: [0, 0.8, 0], up: [0, 1, 0], fov: 38 },
  image: { width: 256, height: 192 },
  render: { maxBounces: 3 },
  environment: { color: [0.55, 0.7, 1.0], intensity: 0.2 },
  ground: { height: 0, material: { color: [0.75, 0.75, 0.72], roughness: 1 } },
  lights: [SPOT, PANEL, SUN],
  spheres: [
    { center: [-1.2, 0.8, 0], radius: 0.8, material: { color: [0.85, 0.2, 0.2], roughness: 1 } },
    { center: [1.2, 0.6, -0.4], radius: 0.6, material: { color: [0.9, 0.75, 0.3], roughness: 0.4 } },
  ],
});
const aspect = scene.image.width / scene.image.height;

type Lights = { type: string; position?: Vec3; target?: Vec3; direction?: Vec3 }[];
const lights = async (page: Page) => (await savedScene(page)).lights as Lights;

/** A handle's centre in client pixels (the overlay lies over the canvas), or null while it is hidden. */
async function handle(page: Page, testId: 'move-handle' | 'aim-handle'): Promise<{ x: number; y: number } | null> {
  const circle = page.getByTestId(testId);
  if ((await circle.getAttribute('display')) !== 'inline' || !(await page.locator('#overlay').isVisible())) return null;
  const box = (await page.locator('#overlay').boundingBox())!;
  return { x: box.x + Number(await circle.getAttribute('cx')), y: box.y + Number(await circle.getAttribute('cy')) };
}

/** Where the marker of light `index` is drawn, in client pixels. */
async function sunMarker(page: Page, index: number): Promise<{ x: number; y: number }> {
  const transform = await page.locator(`[data-testid="sun-marker"][data-light="${index}"]`).getAttribute('transform');
  const [, x, y] = /translate\(([-\d.]+) ([-\d.]+)\)/.exec(transform ?? '')!;
  const box = (await page.locator('#overlay').boundingBox())!;
  return { x: box.x + Number(x), y: box.y + Number(y) };
}

/** Rounded to whole pixels: the mouse is moved there, and the expected result is computed for the same point. */
const whole = (p: { x: number; y: number }) => ({ x: Math.round(p.x), y: Math.round(p.y) });

/** Drags from `from` to `to` and waits for the accumulation to restart (each drag re-uploads the scene). */
async function dragTo(page: Page, from: { x: number; y: number }, to: { x: number; y: number }): Promise<void> {
  const restarts = await watchRestarts(page);
  await drag(page, from, to.x - from.x, to.y - from.y);
  await waitForRestart(restarts);
}

/** The selection folder's title. */
const selectionTitle = (page: Page) => page.locator('.lil-root > .lil-children > .lil-gui > .lil-title').first().textContent();

/** How far the handle is drawn from a client point (Infinity while it is hidden). */
async function handleFrom(page: Page, testId: 'move-handle' | 'aim-handle', p: { x: number; y: number }): Promise<number> {
  const h = await handle(page, testId);
  return h ? Math.hypot(h.x - p.x, h.y - p.y) : Infinity;
}

/**
 * The panel's object list and the sun markers, by keyboard: the list follows
 * a selection made by the pointer, picks an object as a click does (its
 * folder, its handles), takes Delete, Escape and Ctrl+Z, and lists the
 * lights again after a delete and its undo; Enter or Space on a marker
 * selects its light. Starts with light 4 (directional) selected.
 */
async function selectWithoutPointer(page: Page, camera: Camera, seen: (camera: Camera, p: Vec3) => { x: number; y: number }): Promise<void> {
  const list = page.locator('#panel select[data-shortcuts]');
  const listed = ['none', 'light 1: spot', 'light 2: rectangle', 'light 3: directional', 'light 4: directional', 'sphere 1', 'sphere 2'];
  expect(await list.locator('option').allTextContents()).toEqual(listed);
  expect(await list.inputValue(), 'follows the marker drag').toBe('light 4: directional');

  // By keyboard: Home (none), then the arrow down to the spot; selected as a click selects it.
  await list.focus();
  await page.keyboard.press('Home');
  await expect.poll(() => selectionTitle(page)).toBe('Selection (click an object)');
  await page.keyboard.press('ArrowDown');
  await expect.poll(() => selectionTitle(page)).toBe('Selected light 1: spot');
  const spotAt = seen(camera, (await lights(page))[0].position!);
  await expect.poll(() => handleFrom(page, 'move-handle', spotAt), { message: 'its move handle on it' }).toBeLessThan(1);
  expect(await page.locator('#panel .lil-name', { hasText: /^cutoff/ }).count(), "the spot's controls").toBeGreaterThan(0);
  // Escape in the list deselects (list.press: reading the scene clicked "Save JSON", which took the focus).
  await list.press('Escape');
  await expect.poll(() => list.inputValue()).toBe('none');
  expect(await handle(page, 'move-handle')).toBeNull();

  // A click on a sphere: the list shows it.
  const sphereAt = seen(camera, [-1.2, 0.8, 0]);
  await page.mouse.click(Math.round(sphereAt.x), Math.round(sphereAt.y));
  await expect.poll(() => list.inputValue()).toBe('sphere 1');
  expect(await selectionTitle(page)).toBe('Selected sphere 1');

  // Delete in the list removes what it chose (light 4: the scene keeps a directional light, so its program); the list
  // follows, and follows the undo.
  await list.selectOption({ label: 'light 4: directional' });
  await expect.poll(() => selectionTitle(page)).toBe('Selected light 4: directional');
  await list.press('Delete');
  await expect.poll(async () => (await lights(page)).length).toBe(3);
  expect(await list.locator('option').allTextContents()).toEqual(listed.filter((l) => l !== 'light 4: directional'));
  expect(await list.inputValue()).toBe('none');
  await list.press('Control+z');
  await expect.poll(async () => (await lights(page)).length).toBe(4);
  expect(await list.locator('option').allTextContents()).toEqual(listed);

  // A marker is a named button: focusable, Enter selects its light (its aim handle on it), Space another's.
  const marker = (index: number) => page.locator(`[data-testid="sun-marker"][data-light="${index}"]`);
  const about = await marker(2).evaluate((m) => [m.getAttribute('role'), m.getAttribute('aria-label'), m.getAttribute('tabindex'), m.closest('[aria-hidden="true"]') === null]);
  expect(about).toEqual(['button', 'light 3: directional', '0', true]);
  await marker(2).focus();
  expect(await marker(2).evaluate((m) => document.activeElement === m), 'focusable').toBe(true);
  await page.keyboard.press('Enter');
  await expect.poll(() => selectionTitle(page)).toBe('Selected light 3: directional');
  expect(await list.inputValue()).toBe('light 3: directional');
  expect(await handleFrom(page, 'aim-handle', await sunMarker(page, 2))).toBeLessThan(1);
  await marker(3).focus();
  await page.keyboard.press(' ');
  await expect.poll(() => list.inputValue()).toBe('light 4: directional');
  // Delete and Escape work on a light a marker chose: Escape deselects.
  await page.keyboard.press('Escape');
  await expect.poll(() => list.inputValue()).toBe('none');
}

describe('page: light handles', () => {
  it('moves and aims a spot and turns a directional light by their handles, one undo step each, with no recompile', async () => {
    const started = performance.now();
    const { page, errors } = await openPage(harness(), { hash: shareHash(scene), initScript: instrument });
    await expect.poll(async () => (await lights(page)).map((l) => l.type), { timeout: 120_000 }).toEqual(['spot', 'rectangle', 'directional']);
    await waitForSpp(page, 2, 120_000);
    const linksLoaded = (await probe(page)).links;
    const box = (await page.getByTestId('viewport').boundingBox())!;
    /** The camera ray through a client point (as the page's rayAt computes it). */
    const ray = (p: { x: number; y: number }, camera: Camera = scene.camera) => cameraRay(camera, aspect, (p.x - box.x) / box.width, (p.y - box.y) / box.height);
    const seen = (camera: Camera, p: Vec3) => {
      const at = projectPoint(camera, aspect, p)!;
      return { x: box.x + at.u * box.width, y: box.y + at.v * box.height };
    };

    // Click the spot to select it: its handles appear, the move handle where the light is drawn.
    const spotAt = projectPoint(scene.camera, aspect, SPOT.position as Vec3)!;
    const click = await canvasPoint(page, spotAt.u, spotAt.v);
    expect(await handle(page, 'move-handle')).toBeNull();
    await page.mouse.click(click.x, click.y);
    await expect.poll(() => handle(page, 'move-handle')).not.toBeNull();
    const move = (await handle(page, 'move-handle'))!;
    expect(Math.hypot(move.x - click.x, move.y - click.y)).toBeLessThan(1);

    // The move handle: the light follows the cursor in the plane facing the camera.
    const moveFrom = whole(move);
    const moveTo = { x: moveFrom.x + 40, y: moveFrom.y - 30 };
    await dragTo(page, moveFrom, moveTo);
    const spotLight = structuredClone(scene.lights[0]);
    const expectedMove = draggedLight({ kind: 'move', index: 0, light: spotLight, camera: scene.camera, start: ray(moveFrom) }, ray(moveTo), null) as { position: Vec3 };
    let now = await lights(page);
    now[0].position!.forEach((x, i) => expect(x).toBeCloseTo(expectedMove.position[i], 3));
    // Under the cursor (less the grab's offset from the handle's centre), at the same depth.
    const movedAt = projectPoint(scene.camera, aspect, now[0].position!)!;
    const grab = { x: moveFrom.x - move.x, y: moveFrom.y - move.y };
    expect(Math.hypot(box.x + movedAt.u * box.width + grab.x - moveTo.x, box.y + movedAt.v * box.height + grab.y - moveTo.y)).toBeLessThan(0.1);
    expect(movedAt.depth).toBeCloseTo(spotAt.depth, 3);
    expect(now[0].target).toEqual(SPOT.target);
    const moved = now[0].position!;
    await page.keyboard.press('Control+z');
    expect((await lights(page))[0].position, 'one undo puts it back').toEqual(SPOT.position);
    await page.keyboard.press('Control+Shift+z');
    expect((await lights(page))[0].position).toEqual(moved);

    // The aim handle: the target goes onto the ground under the cursor.
    const aim = whole((await handle(page, 'aim-handle'))!);
    const targetAt = projectPoint(scene.camera, aspect, SPOT.target as Vec3)!;
    expect(Math.hypot(aim.x - (box.x + targetAt.u * box.width), aim.y - (box.y + targetAt.v * box.height))).toBeLessThan(1);
    const groundPoint: Vec3 = [-0.2, 0, 2];
    const ground = projectPoint(scene.camera, aspect, groundPoint)!;
    const aimTo = whole(await canvasPoint(page, ground.u, ground.v));
    await dragTo(page, aim, aimTo);
    now = await lights(page);
    expect(now[0].target![1], 'on the ground').toBeCloseTo(0, 9);
    now[0].target!.forEach((x, i) => expect(x).toBeCloseTo(groundPoint[i], 1));
    expect(now[0].position).toEqual(moved);
    await page.keyboard.press('Control+z');
    expect((await lights(page))[0], 'one undo restores the target, keeps the move').toMatchObject({ position: moved, target: SPOT.target });

    // A rectangle: click it to select it, then aim it at the ground under the cursor (its rotation turns).
    const panelAt = projectPoint(scene.camera, aspect, PANEL.position as Vec3)!;
    const panelClick = whole(await canvasPoint(page, panelAt.u + 0.01, panelAt.v));
    await page.mouse.click(panelClick.x, panelClick.y);
    const panelCenter = await canvasPoint(page, panelAt.u, panelAt.v);
    const fromPanel = async () => {
      const h = await handle(page, 'move-handle');
      return h ? Math.hypot(h.x - panelCenter.x, h.y - panelCenter.y) : Infinity;
    };
    await expect.poll(fromPanel, { message: 'the rectangle is selected: its move handle on it' }).toBeLessThan(1);
    const panelAim = whole((await handle(page, 'aim-handle'))!);
    const floor: Vec3 = [-0.6, 0, 2.2];
    const floorAt = projectPoint(scene.camera, aspect, floor)!;
    await dragTo(page, panelAim, whole(await canvasPoint(page, floorAt.u, floorAt.v)));
    const panel = (await lights(page))[1] as unknown as { position: Vec3; rotation: Vec3 };
    expect(panel.position).toEqual(PANEL.position);
    const facing = emitDirection(panel.rotation);
    const wanted = floor.map((x, i) => x - PANEL.position[i]);
    const cosine = (facing[0] * wanted[0] + facing[1] * wanted[1] + facing[2] * wanted[2]) / Math.hypot(...wanted);
    expect(cosine, 'faces the ground point').toBeGreaterThan(0.999);
    await page.keyboard.press('Control+z');
    expect((await lights(page))[1], 'one undo turns it back').toEqual(PANEL);

    // A directional light (added: the scene has one already, so the same program) turns with its handle.
    await page.selectOption('#light-kind', 'directional');
    await page.click('#add-light');
    await expect.poll(async () => (await lights(page)).length).toBe(4);
    const added = (await lights(page))[3] as unknown as Extract<Light, { type: 'directional' }>;
    expect(await handle(page, 'move-handle'), 'no position: no move handle').toBeNull();
    const sunFrom = whole((await handle(page, 'aim-handle'))!);
    const sunTo = { x: sunFrom.x - 50, y: sunFrom.y + 35 };
    await dragTo(page, sunFrom, sunTo);
    const expectedSun = draggedLight({ kind: 'aim', index: 3, light: added, camera: scene.camera, start: ray(sunFrom) }, ray(sunTo), null) as { direction: Vec3 };
    const sun = (await lights(page))[3].direction!;
    sun.forEach((x, i) => expect(x).toBeCloseTo(expectedSun.direction[i], 3));
    const unitBefore = added.direction.map((x) => x / Math.hypot(...added.direction));
    expect(Math.hypot(...sun.map((x, i) => x - unitBefore[i])), 'turned').toBeGreaterThan(0.2);
    // Where the handle is drawn now is where the math puts it.
    const drawn = (await handle(page, 'aim-handle'))!;
    const sunHandle = projectPoint(scene.camera, aspect, handlePoints({ ...added, direction: sun }, scene.camera).aim!)!;
    expect(Math.hypot(drawn.x - (box.x + sunHandle.u * box.width), drawn.y - (box.y + sunHandle.v * box.height))).toBeLessThan(1);
    await page.keyboard.press('Control+z');
    expect((await lights(page))[3].direction, 'one undo turns it back').toEqual(added.direction);

    // Escape during a drag cancels it: the light turns back at once, the rest of the press does nothing, no undo step
    // is recorded (the redo step survives), and the light stays selected.
    expect(await page.locator('#redo').isEnabled()).toBe(true);
    const fromHandle = async () => {
      const h = await handle(page, 'aim-handle');
      return h ? Math.hypot(h.x - sunFrom.x, h.y - sunFrom.y) : Infinity;
    };
    await page.mouse.move(sunFrom.x, sunFrom.y);
    await page.mouse.down();
    await page.mouse.move(sunTo.x, sunTo.y, { steps: 8 });
    await expect.poll(fromHandle, { message: 'the drag turns it' }).toBeGreaterThan(20);
    await page.keyboard.press('Escape');
    await expect.poll(fromHandle, { message: 'Escape turns it back' }).toBeLessThan(1);
    await page.mouse.move(sunTo.x + 30, sunTo.y - 20, { steps: 4 });
    await page.mouse.up();
    expect((await lights(page))[3].direction, 'cancelled').toEqual(added.direction);
    expect(await fromHandle(), 'still selected, unmoved').toBeLessThan(1);
    expect(await page.locator('#redo').isEnabled(), 'no undo step recorded: the redo stack is kept').toBe(true);

    // The autosave holds the edits (its record: src/app/persistence.ts).
    await page.waitForFunction(() => document.body.dataset.saved === 'saved');
    const autosaved = await page.evaluate(
      () =>
        new Promise<string>((resolve, reject) => {
          const open = indexedDB.open('pathtrace');
          open.onerror = () => reject(open.error);
          open.onsuccess = () => {
            const get = open.result.transaction('keyval').objectStore('keyval').get('autosave');
            get.onsuccess = () => resolve(get.result as string);
            get.onerror = () => reject(get.error);
          };
        }),
    );
    expect((JSON.parse(autosaved).scene as { lights: Lights }).lights).toEqual(await lights(page));

    // Away from the handles a drag still orbits, and leaves the light where it is.
    const before = await savedScene(page);
    const sky = whole(await canvasPoint(page, 0.9, 0.1));
    await dragTo(page, sky, { x: sky.x - 60, y: sky.y + 10 });
    const after = await savedScene(page);
    expect(after.camera).not.toEqual(before.camera);
    expect(after.lights).toEqual(before.lights);
    // Escape deselects: the handles go.
    await page.keyboard.press('Escape');
    await expect.poll(() => handle(page, 'aim-handle')).toBeNull();

    // Deselected, each directional light still shows its sun marker, where its aim handle goes (for the orbited camera).
    const orbited = parseScene(after).camera;
    await expect.poll(() => page.getByTestId('sun-marker').count()).toBe(2);
    const suns = [2, 3].map((i) => handlePoints(parseScene(after).lights[i], orbited).aim!);
    for (const [k, index] of [2, 3].entries()) {
      const drawnAt = await sunMarker(page, index);
      const expected = seen(orbited, suns[k]);
      expect(Math.hypot(drawnAt.x - expected.x, drawnAt.y - expected.y), `light ${index + 1}'s marker`).toBeLessThan(1);
    }
    // A click on one selects that light (its aim handle on the marker) and neither orbits nor turns it.
    const sunClick = whole(await sunMarker(page, 2));
    await page.mouse.click(sunClick.x, sunClick.y);
    await expect.poll(() => page.locator('#panel').textContent()).toContain('Selected light 3');
    const selectedAim = (await handle(page, 'aim-handle'))!;
    expect(Math.hypot(selectedAim.x - sunClick.x, selectedAim.y - sunClick.y)).toBeLessThan(1);
    // A drag from another's marker selects that one and turns it (as its aim handle would), the camera left alone.
    const otherFrom = whole(await sunMarker(page, 3));
    const otherTo = { x: otherFrom.x + 45, y: otherFrom.y - 25 };
    await drag(page, otherFrom, otherTo.x - otherFrom.x, otherTo.y - otherFrom.y);
    await expect.poll(() => page.locator('#panel').textContent()).toContain('Selected light 4');
    const turned = await savedScene(page);
    expect(turned.camera, 'no orbit').toEqual(after.camera);
    expect((turned.lights as Lights)[2], 'the clicked one is unturned').toEqual((after.lights as Lights)[2]);
    const before3 = parseScene(after).lights[3];
    const expectedTurn = draggedLight({ kind: 'aim', index: 3, light: before3, camera: orbited, start: ray(otherFrom, orbited) }, ray(otherTo, orbited), null) as { direction: Vec3 };
    (turned.lights as Lights)[3].direction!.forEach((x, i) => expect(x).toBeCloseTo(expectedTurn.direction[i], 3));

    const keyboardStarted = performance.now();
    await selectWithoutPointer(page, orbited, seen);
    console.log(`light handles, object list and markers by keyboard: ${((performance.now() - keyboardStarted) / 1000).toFixed(1)} s`);

    await waitForSpp(page, 2);
    expect((await probe(page)).links - linksLoaded, 'handle drags, undo and redo, selecting from the list or a marker link no program').toBe(0);
    expect(errors).toEqual([]);
    await page.close();
    console.log(`light handles: ${((performance.now() - started) / 1000).toFixed(1)} s`);
  }, 300_000);
});
