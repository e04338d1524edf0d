/**
 * The selected sphere's or mesh's material controls: the material's kind,
 * the kind's own controls (its description's `controls`, as data:
 * src/materials/<kind>/kind.ts) and emission. The ground keeps the panel's
 * color and roughness (every kind has them; no emission there).
 *
 * The edits themselves are pure functions of a material, so they are tested
 * without a page; the controls only wire them into `app.live`.
 */
import type GUI from 'lil-gui';
import type { Controller } from 'lil-gui';
import type { MaterialControl } from '../materials/kind';
import { kindLabel, MATERIAL_TYPE_NAMES, materialControls, switchMaterialType } from '../materials/registry';
import { hexToLinear, linearToHex } from '../scene/color';
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

/** Per sphere object (stable during edits; undo and load replace it): what switching and zero intensity set aside. */
interface SetAside {
  byType: Partial<Record<MaterialType, Material>>;
  emissionColor: Vec3;
}
const setAside = new WeakMap<Sphere, SetAside>();

function setAsideFor(sphere: Sphere): SetAside {
  let entry = setAside.get(sphere);
  if (!entry) setAside.set(sphere, (entry = { byType: {}, emissionColor: [...(sphere.material.emission?.color ?? WHITE)] }));
  return entry;
}

/**
 * Adds the controls for `sphere()`'s material to `folder`. The type-specific
 * ones depend on the type at build time: the panel rebuilds the folder when
 * the type changes (its selection key includes the type).
 */
export function addSphereMaterialControls(
  folder: GUI,
  app: App,
  sphere: () => Sphere,
  tracked: <T extends Controller>(controller: T) => T,
): void {
  const material = () => sphere().material;
  const edit = (mutate: (m: Record<string, unknown>) => void) => app.live(() => mutate(material() as unknown as Record<string, unknown>));
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
  for (const control of materialControls(material())) tracked(addKindControl(folder, control, material, edit));
  addEmissionControls(folder, app, sphere, tracked);
}

/** One control of a kind's description (MaterialControl) on the current material. */
function addKindControl(
  folder: GUI,
  control: MaterialControl,
  material: () => Material,
  edit: (mutate: (m: Record<string, unknown>) => void) => void,
): Controller {
  const value = () => (material() as unknown as Record<string, unknown>)[control.key];
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
