/**
 * The selected sphere's or mesh's material controls: the material's kind,
 * the kind's own controls (its description's `controls`, as data:
 * src/materials/<kind>/kind.ts) and emission. The ground keeps the panel's
 * color and roughness (every kind has them; no emission there).
 *
 * An input that may be a texture (a `texturable` control, or a `texture`
 * one) shows, on an object with texture coordinates (`TextureSlots`), its
 * constant with an "image…" button or, while it is a texture, a slot with
 * the image's name and size, "image…" and "clear"; an image dropped on
 * either row is used too. The panel rebuilds the controls when an input
 * turns from a constant into a texture or back (materialLayoutKey).
 *
 * The edits themselves are pure functions of a material, so they are tested
 * without a page; the controls only wire them into `app.live`.
 */
import type GUI from 'lil-gui';
import type { Controller } from 'lil-gui';
import type { MaterialControl } from '../materials/kind';
import { controlTextureInput, inputDefault, kindLabel, MATERIAL_TYPE_NAMES, materialControls, materialTextures, switchMaterialType } from '../materials/registry';
import { hexToLinear, linearToHex } from '../scene/color';
import { isTexture, type Texture } from '../scene/texture/texture';
import type { Emission, Material, MaterialType, Vec3 } from '../scene/types';
import type { App } from './App';

export { switchMaterialType };

/** A sphere or a mesh: anything with a material. */
type Sphere = { material: Material };

export const MATERIAL_TYPES: readonly MaterialType[] = MATERIAL_TYPE_NAMES as readonly MaterialType[];

const WHITE: Vec3 = [1, 1, 1];
const MAX_EMISSION_INTENSITY = 100;

/**
 * Sets the emitted intensity. 0 removes the `emission` key (no emission is
 * the format's default, so the saved scene stays minimal and, without other
 * version-2 keys, stays version 1); `color` is used when emission starts.
 */
export function withEmissionIntensity(material: Material, intensity: number, color: Vec3): void {
  if (!(intensity > 0)) {
    delete material.emission;
    return;
  }
  if (material.emission) material.emission.intensity = intensity;
  else material.emission = { color: [...color], intensity };
}

/**
 * Makes input `key` a texture of `image`. A texture already there keeps its
 * channel, scale and uv transform (only the image changes); a constant
 * becomes the image as it is (scale 1, channel "r", no uv transform).
 */
export function withTexture(material: Material, key: string, image: string): void {
  const m = material as unknown as Record<string, unknown>;
  const current = m[key];
  m[key] = isTexture(current)
    ? { ...structuredClone(current), image }
    : ({ image, channel: 'r', scale: 1, uv: { offset: [0, 0], scale: [1, 1], rotation: 0 } } satisfies Texture);
}

/** Makes input `key` a constant again: `constant`, else the kind's default (an input that is only ever a texture is removed). */
export function withoutTexture(material: Material, key: string, constant?: unknown): void {
  const m = material as unknown as Record<string, unknown>;
  const value = constant !== undefined && !isTexture(constant) ? structuredClone(constant) : inputDefault(material, key);
  if (value === undefined) delete m[key];
  else m[key] = value;
}

/** What the controls of `m` depend on besides its values: its kind and which inputs are textures (of which images). */
export function materialLayoutKey(m: Material): string {
  return `${m.type}:${materialTextures(m).map((t) => `${t.key}=${t.texture.image}`).join(',')}`;
}

/** The texture slots of one object's material (only objects with texture coordinates have them: not spheres). */
export interface TextureSlots {
  /** Makes input `key` a texture of the image in `file` (decoded off the main thread; a file that cannot be used changes nothing). */
  useFile(key: string, file: File): void;
  /** Asks the user for an image for input `key` (then as useFile). */
  openFilePicker(key: string): void;
  /** The slot's text for a loaded image: its name and size. */
  describe(image: string): string;
}

/** Per sphere object (stable during edits; undo and load replace it): what switching, zero intensity and a texture set aside. */
interface SetAside {
  byType: Partial<Record<MaterialType, Material>>;
  emissionColor: Vec3;
  /** The constants that textures replaced, by key (clearing the texture brings them back). */
  constants: Record<string, unknown>;
}
const setAside = new WeakMap<Sphere, SetAside>();

function setAsideFor(sphere: Sphere): SetAside {
  let entry = setAside.get(sphere);
  if (!entry) setAside.set(sphere, (entry = { byType: {}, emissionColor: [...(sphere.material.emission?.color ?? WHITE)], constants: {} }));
  return entry;
}

/**
 * Adds the controls for `sphere()`'s material to `folder`. The type-specific
 * ones depend on the type at build time, and which inputs are textures: the
 * panel rebuilds the folder when they change (its selection key includes
 * materialLayoutKey).
 */
export function addSphereMaterialControls(
  folder: GUI,
  app: App,
  sphere: () => Sphere,
  tracked: <T extends Controller>(controller: T) => T,
  slots?: TextureSlots,
): void {
  const material = () => sphere().material;
  const labels = Object.fromEntries(MATERIAL_TYPES.map((t) => [kindLabel(t), t]));
  tracked(folder.add({
    get type() { return material().type; },
    set type(to: MaterialType) {
      app.live(() => {
        const s = sphere();
        const aside = setAsideFor(s);
        aside.byType[s.material.type] = structuredClone(s.material);
        s.material = switchMaterialType(s.material, to, aside.byType[to]);
      });
    },
  }, 'type', labels).name('material'));
  for (const control of materialControls(material())) addMaterialInput(folder, app, control, sphere, tracked, slots);
  addEmissionControls(folder, app, sphere, tracked);
}

/**
 * The control of one input of `owner()`'s material: its constant's or, with
 * `slots`, while it is a texture, its texture slot (a texturable constant
 * then has an "image…" button and takes dropped images). Null for an input
 * that is only ever a texture, without slots.
 */
export function addMaterialInput(
  folder: GUI,
  app: App,
  control: MaterialControl,
  owner: () => Sphere,
  tracked: <T extends Controller>(controller: T) => T,
  slots?: TextureSlots,
): Controller | null {
  const material = () => owner().material;
  const edit = (mutate: (m: Record<string, unknown>) => void) => app.live(() => mutate(material() as unknown as Record<string, unknown>));
  const textured = slots && controlTextureInput(control) !== null;
  const value = () => (material() as unknown as Record<string, unknown>)[control.key];
  if (textured && (control.control === 'texture' || isTexture(value()))) {
    return addTextureSlot(folder, control, value, slots, () => app.edit(() => withoutTexture(material(), control.key, setAsideFor(owner()).constants[control.key])));
  }
  if (control.control === 'texture') return null; // no texture coordinates: nothing to show
  const controller = tracked(addKindControl(folder, control, material, edit));
  if (textured) {
    // The constant is set aside before the image loads: clearing the texture brings it back.
    const setAsideThen = (action: () => void) => {
      setAsideFor(owner()).constants[control.key] = structuredClone(value());
      action();
    };
    addImageButton(controller.$widget, () => setAsideThen(() => slots.openFilePicker(control.key)));
    acceptImageDrops(controller.domElement, (file) => setAsideThen(() => slots.useFile(control.key, file)));
  }
  return controller;
}

/**
 * A texture slot: the image's name and size (read-only text), "image…" to
 * open another and "clear" (back to the constant); images dropped on it
 * replace its image. For an input that is only ever a texture and is
 * absent, the text says "none" and there is nothing to clear.
 */
function addTextureSlot(folder: GUI, control: MaterialControl, value: () => unknown, slots: TextureSlots, clear: () => void): Controller {
  const shown = {
    get value() {
      const v = value();
      return isTexture(v) ? slots.describe(v.image) : 'none';
    },
    set value(_: string) {},
  };
  const controller = folder.add(shown, 'value').name(control.label);
  const input = controller.domElement.querySelector('input');
  if (input) {
    input.readOnly = true;
    input.title = shown.value; // the panel is narrow: the whole name on hover (the panel rebuilds the slot for another image)
  }
  controller.domElement.classList.add('texture-slot');
  controller.domElement.dataset.textureKey = control.key;
  addImageButton(controller.$widget, () => slots.openFilePicker(control.key));
  if (isTexture(value())) addButton(controller.$widget, 'clear', `Use a constant ${control.label} instead of the image`, clear);
  acceptImageDrops(controller.domElement, (file) => slots.useFile(control.key, file));
  return controller;
}

function addButton(parent: HTMLElement, text: string, title: string, action: () => void): HTMLButtonElement {
  const button = document.createElement('button');
  button.type = 'button';
  button.className = 'texture-button';
  button.textContent = text;
  button.title = title;
  button.addEventListener('click', action);
  parent.append(button);
  return button;
}

const addImageButton = (parent: HTMLElement, action: () => void) =>
  addButton(parent, 'image…', 'Use an image (PNG, JPEG, WebP, EXR or HDR); you can also drop one here', action);

/**
 * Takes an image dropped on `row`. The event's default is prevented, which
 * tells the page's own drop handler (main.ts: scenes, maps, models) that it
 * was taken.
 */
function acceptImageDrops(row: HTMLElement, use: (file: File) => void): void {
  const files = (event: DragEvent) => event.dataTransfer?.types.includes('Files') ?? false;
  row.addEventListener('dragover', (event) => {
    if (!files(event)) return;
    event.preventDefault();
    row.classList.add('texture-drop');
  });
  row.addEventListener('dragleave', () => row.classList.remove('texture-drop'));
  row.addEventListener('drop', (event) => {
    row.classList.remove('texture-drop');
    const file = event.dataTransfer?.files[0];
    if (!file) return;
    event.preventDefault();
    use(file);
  });
}

/** One control of a kind's description (MaterialControl) on the current material. */
function addKindControl(
  folder: GUI,
  control: MaterialControl,
  material: () => Material,
  edit: (mutate: (m: Record<string, unknown>) => void) => void,
): Controller {
  const value = () => (material() as unknown as Record<string, unknown>)[control.key];
  if (control.control === 'texture') throw new Error(`${control.key}: a texture-only input has no constant control`);
  if (control.control === 'color') {
    return folder.addColor({
      get value() { return linearToHex(value() as Vec3); },
      set value(v: string) { edit((m) => (m[control.key] = hexToLinear(v))); },
    }, 'value').name(control.label);
  }
  if (control.control === 'number') {
    return folder.add({
      get value() { return value() as number; },
      set value(v: number) { edit((m) => (m[control.key] = v)); },
    }, 'value', control.min, control.max, control.step).name(control.label);
  }
  const get = control.get as ((m: Material) => string) | undefined;
  const set = control.set as ((m: Material, option: string) => void) | undefined;
  return folder.add({
    get value() { return get ? get(material()) : String(value()); },
    set value(v: string) { edit((m) => (set ? set(m as unknown as Material, v) : (m[control.key] = v))); },
  }, 'value', [...control.options]).name(control.label);
}

function addEmissionControls(folder: GUI, app: App, sphere: () => Sphere, tracked: <T extends Controller>(controller: T) => T): void {
  const emission = (): Emission | undefined => sphere().material.emission;
  tracked(folder.addColor({
    get color() { return linearToHex(emission()?.color ?? setAsideFor(sphere()).emissionColor); },
    set color(v: string) {
      // Without emission the color waits for the intensity: no key, no scene change.
      setAsideFor(sphere()).emissionColor = hexToLinear(v);
      if (emission()) app.live(() => (emission()!.color = hexToLinear(v)));
    },
  }, 'color').name('emission color'));
  tracked(folder.add({
    get intensity() { return emission()?.intensity ?? 0; },
    set intensity(v: number) {
      app.live(() => {
        const s = sphere();
        const aside = setAsideFor(s);
        if (s.material.emission) aside.emissionColor = [...s.material.emission.color];
        withEmissionIntensity(s.material, v, aside.emissionColor);
      });
    },
  }, 'intensity', 0, MAX_EMISSION_INTENSITY, 0.1).name('emission intensity'));
}
