/**
 * Pointer, wheel and keyboard input on the viewport.
 * Mouse: drag orbits, right- or shift-drag pans, wheel zooms; a press on a
 * sphere or light selects it and drags it over the ground plane (shift lifts
 * it); a press on a selected light's handle moves it in the plane facing the
 * camera (the move handle) or aims it (the aim handle: lightHandles.ts); a
 * press on a directional light's marker (its "sun") selects it and aims it
 * the same way; Escape during a handle or object drag cancels it (the
 * scene goes back, no undo step), else deselects; double-click focuses the lens. Touch: one finger orbits (or drags the
 * object or handle under it), two fingers pinch-zoom and pan.
 */
import { intersectPlaneY } from '../scene/picking';
import type { App } from './App';
import { orbit, pan, zoom } from './cameraControls';
import type { HandleDrag } from './lightHandles';

type Gesture =
  | { type: 'orbit' | 'pan'; moved: boolean }
  | { type: 'object'; moved: boolean }
  | { type: 'handle'; moved: boolean; drag: HandleDrag }
  | { type: 'pinch'; moved: boolean; distance: number; midX: number; midY: number };

/** Radians of orbit per CSS pixel. */
const ORBIT_SPEED = 0.008;
/** Pixels a press may wander and still count as a click. */
const CLICK_SLOP = 3;
/** CSS pixels from a handle's centre that still grab it (a finger is less precise). */
const HANDLE_REACH = { mouse: 9, touch: 18 };

/** What the keyboard needs of the pointer input. */
export interface ViewportInput {
  /** Cancels a handle or object drag in progress (the scene goes back, no undo step); false if none is. */
  cancelDrag(): boolean;
}

export function attachInput(app: App, canvas: HTMLCanvasElement): ViewportInput {
  const pointers = new Map<number, { x: number; y: number; startX: number; startY: number }>();
  let gesture: Gesture | null = null;
  let wheelTimer = 0;

  const heightPx = () => Math.max(1, canvas.clientHeight);

  const finish = () => {
    // A handle press opened an edit even if it never moved: close it.
    if (gesture?.moved || gesture?.type === 'handle') app.endEdit();
    gesture = null;
  };

  canvas.addEventListener('contextmenu', (event) => event.preventDefault());

  canvas.addEventListener('pointerdown', (event) => {
    // A new gesture closes any edit still open (a panel field whose finishing
    // event has not come), so the gesture is an undo step of its own.
    if (pointers.size === 0) app.endEdit();
    canvas.setPointerCapture(event.pointerId);
    pointers.set(event.pointerId, { x: event.clientX, y: event.clientY, startX: event.clientX, startY: event.clientY });
    if (pointers.size === 2) {
      finish();
      const [a, b] = [...pointers.values()];
      gesture = { type: 'pinch', moved: false, distance: Math.hypot(a.x - b.x, a.y - b.y), midX: (a.x + b.x) / 2, midY: (a.y + b.y) / 2 };
      return;
    }
    if (pointers.size > 2) return;
    // The selected light's handles and the directional lights' markers come before what lies under them (shift
    // keeps lifting the light or panning); anywhere else the press orbits, pans or picks as before.
    const drag = event.button === 0 && !event.shiftKey ? handleDragAt(app, event.clientX, event.clientY, handleReach(event)) : null;
    if (drag) {
      gesture = { type: 'handle', moved: false, drag };
      return;
    }
    const hit = event.button === 0 ? app.pick(event.clientX, event.clientY) : null;
    if (hit) {
      app.select({ kind: hit.kind, index: hit.index });
      gesture = { type: 'object', moved: false };
    } else if (event.button === 2 || event.button === 1 || event.shiftKey) {
      gesture = { type: 'pan', moved: false };
    } else {
      gesture = { type: 'orbit', moved: false };
    }
  });

  canvas.addEventListener('pointermove', (event) => {
    const pointer = pointers.get(event.pointerId);
    if (pointers.size === 0) canvas.classList.toggle('over-handle', overHandle(app, event.clientX, event.clientY, handleReach(event)));
    if (!pointer || !gesture) return;
    const dx = event.clientX - pointer.x;
    const dy = event.clientY - pointer.y;
    const previous = { x: pointer.x, y: pointer.y };
    pointer.x = event.clientX;
    pointer.y = event.clientY;
    if (!gesture.moved && Math.hypot(event.clientX - pointer.startX, event.clientY - pointer.startY) < CLICK_SLOP) return;
    gesture.moved = true;
    switch (gesture.type) {
      case 'orbit':
        app.live((s) => (s.camera = orbit(s.camera, dx * ORBIT_SPEED, dy * ORBIT_SPEED)), true);
        break;
      case 'pan':
        app.live((s) => (s.camera = pan(s.camera, dx / heightPx(), dy / heightPx())), true);
        break;
      case 'object':
        moveObject(app, previous, { x: event.clientX, y: event.clientY }, event.shiftKey, heightPx());
        break;
      case 'handle':
        app.dragHandle(gesture.drag, event.clientX, event.clientY);
        break;
      case 'pinch': {
        const [a, b] = [...pointers.values()];
        const distance = Math.hypot(a.x - b.x, a.y - b.y);
        const midX = (a.x + b.x) / 2;
        const midY = (a.y + b.y) / 2;
        const factor = distance > 0 && gesture.distance > 0 ? gesture.distance / distance : 1;
        const panX = (midX - gesture.midX) / heightPx();
        const panY = (midY - gesture.midY) / heightPx();
        app.live((s) => (s.camera = pan(zoom(s.camera, factor), panX, panY)), true);
        Object.assign(gesture, { distance, midX, midY });
        break;
      }
    }
  });

  const release = (event: PointerEvent) => {
    if (!pointers.delete(event.pointerId)) return;
    if (gesture?.type === 'orbit' && !gesture.moved && pointers.size === 0) app.select(null);
    if (pointers.size === 0 || gesture?.type === 'pinch') finish();
  };
  canvas.addEventListener('pointerup', release);
  canvas.addEventListener('pointercancel', release);

  canvas.addEventListener('dblclick', (event) => app.focusAt(event.clientX, event.clientY));

  canvas.addEventListener(
    'wheel',
    (event) => {
      event.preventDefault();
      const pixels = event.deltaMode === 1 ? event.deltaY * 16 : event.deltaMode === 2 ? event.deltaY * 400 : event.deltaY;
      const factor = Math.exp(Math.max(-1, Math.min(1, pixels * 0.0015)));
      app.live((s) => (s.camera = zoom(s.camera, factor)), true);
      // A burst of wheel events is one undoable edit.
      clearTimeout(wheelTimer);
      wheelTimer = window.setTimeout(() => app.endEdit(), 300);
    },
    { passive: false },
  );

  return {
    cancelDrag() {
      if (gesture?.type !== 'handle' && gesture?.type !== 'object') return false;
      app.cancelEdit();
      gesture = null; // the rest of the press does nothing
      return true;
    },
  };
}

const handleReach = (event: PointerEvent) => (event.pointerType === 'touch' ? HANDLE_REACH.touch : HANDLE_REACH.mouse);

/**
 * The drag a press at a client point starts: on a handle of the selected
 * light, or on a directional light's marker (it selects the light, whose aim
 * handle is there: a press on it turns it, never orbits); null elsewhere.
 */
function handleDragAt(app: App, x: number, y: number, reach: number): HandleDrag | null {
  const handle = app.handleAt(x, y, reach);
  if (handle) return app.beginHandleDrag(handle, x, y);
  const sun = app.sunMarkerAt(x, y, reach);
  if (sun === null) return null;
  app.select({ kind: 'light', index: sun });
  return app.beginHandleDrag('aim', x, y);
}

const overHandle = (app: App, x: number, y: number, reach: number) => app.handleAt(x, y, reach) !== null || app.sunMarkerAt(x, y, reach) !== null;

/** Drags the selected object over the horizontal plane through its centre, or lifts it (shift). */
function moveObject(app: App, from: { x: number; y: number }, to: { x: number; y: number }, lift: boolean, heightPx: number): void {
  const center = app.selectedCenter();
  if (!center) return;
  const camera = app.scene.camera;
  const depth = Math.hypot(center[0] - camera.position[0], center[1] - camera.position[1], center[2] - camera.position[2]);
  if (lift) {
    const worldPerPixel = (2 * depth * Math.tan((camera.fov * Math.PI) / 360)) / heightPx;
    app.live(() => (center[1] += (from.y - to.y) * worldPerPixel), true);
    return;
  }
  const a = app.rayAt(from.x, from.y);
  const b = app.rayAt(to.x, to.y);
  const ta = intersectPlaneY(a, center[1]);
  const tb = intersectPlaneY(b, center[1]);
  // Near the horizon the plane runs off to infinity: do not fling the object there.
  const far = depth * 20 + 10;
  if (ta === null || tb === null || ta > far || tb > far) return;
  const dx = b.origin[0] + tb * b.direction[0] - (a.origin[0] + ta * a.direction[0]);
  const dz = b.origin[2] + tb * b.direction[2] - (a.origin[2] + ta * a.direction[2]);
  app.live(() => {
    center[0] += dx;
    center[2] += dz;
  }, true);
}

/**
 * Whether a key pressed in `target` belongs to the field (typing): a text
 * field, an editable element, or a select unless it is marked
 * `data-shortcuts` (the panel's object list, where Delete removes and Escape
 * deselects what was chosen in it).
 */
function typingIn(target: HTMLElement | null): boolean {
  if (!target) return false;
  if (target.tagName === 'SELECT') return target.dataset.shortcuts === undefined;
  return target.isContentEditable || /^(INPUT|TEXTAREA)$/.test(target.tagName);
}

/**
 * Keyboard shortcuts, ignored while typing in a field. Taken in the capture
 * phase: lil-gui stops every key pressed in its panel from bubbling, and its
 * buttons and the object list take the shortcuts as the toolbar does.
 */
export function attachKeys(app: App, input: ViewportInput): void {
  window.addEventListener('keydown', (event) => {
    if (typingIn(event.target as HTMLElement | null)) return;
    const mod = event.ctrlKey || event.metaKey;
    const key = event.key.toLowerCase();
    if (mod && key === 'z') {
      event.preventDefault();
      if (event.shiftKey) app.redo();
      else app.undo();
    } else if (mod && key === 'y') {
      event.preventDefault();
      app.redo();
    } else if ((event.key === 'Delete' || event.key === 'Backspace') && app.selection) {
      event.preventDefault();
      app.deleteSelection();
    } else if (event.key === 'Escape') {
      // As in Blender and three.js's editor: Escape cancels a drag; with none, it deselects.
      if (!input.cancelDrag()) app.select(null);
    }
  }, { capture: true });
}
