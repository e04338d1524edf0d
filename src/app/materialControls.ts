/**
 * The selected sphere's or mesh's material controls (scene format version 2): the
 * material type (standard or dielectric), its color or tint, roughness, the
 * dielectric's index of refraction, and emission. The ground keeps the
 * panel's standard-only controls: the format forbids glass and emission there.
 *
 * The edits themselves are pure functions of a material, so they are tested
 * without a page; the controls only wire them into `app.live`.
 */
import type GUI from 'lil-gui';
import type { Controller } from 'lil-gui';
import { hexToLinear, linearToHex } from '../scene/color';
import { MAX_IOR, MIN_IOR } from '../scene/limits';
import type { Emission, Material, MaterialType, Vec3 } from '../scene/types';
import type { App } from './App';

/** A sphere or a mesh: anything with a material. */
type Sphere = { material: Material };

export const MATERIAL_TYPES: readonly MaterialType[] = ['standard', 'dielectric'];

/** Clear glass, what "make it glass" means: untinted, smooth, ior of window glass. */
const NEW_GLASS = { color: [1, 1, 1] as Vec3, roughness: 0, ior: 1.5 };
const WHITE: Vec3 = [1, 1, 1];
const MAX_EMISSION_INTENSITY = 100;

/**
 * The material after switching `current` to type `to`. Emission is kept.
 * With `remembered` (the sphere's last material of that type in this
 * session) its parameters come back, so switching back and forth loses
 * nothing. Otherwise standard -> dielectric gives clear glass (a standard
 * albedo used as a per-crossing tint would make dark, saturated glass), and
 * dielectric -> standard keeps the tint as the color and the roughness.
 */
export function switchMaterialType(current: Material, to: MaterialType, remembered?: Material): Material {
  if (current.type === to) return structuredClone(current);
  const emission = current.emission ? { emission: structuredClone(current.emission) } : {};
  if (remembered?.type === to) {
    const { emission: _dropped, ...parameters } = structuredClone(remembered);
    return { ...parameters, ...emission };
  }
  if (to === 'dielectric') return { type: 'dielectric', color: [...NEW_GLASS.color], roughness: NEW_GLASS.roughness, ior: NEW_GLASS.ior, ...emission };
  return { type: 'standard', color: [...current.color], roughness: current.roughness, ...emission };
}

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
  const edit = (mutate: (m: Material) => void) => app.live(() => mutate(material()));
  const isGlass = material().type === 'dielectric';
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
  }, 'type', [...MATERIAL_TYPES]).name('material'));
  tracked(folder.addColor({
    get color() { return linearToHex(material().color); },
    set color(v: string) { edit((m) => (m.color = hexToLinear(v))); },
  }, 'color').name(isGlass ? 'tint' : 'color'));
  tracked(folder.add({
    get roughness() { return material().roughness; },
    set roughness(v: number) { edit((m) => (m.roughness = v)); },
  }, 'roughness', 0, 1, 0.01));
  if (isGlass) {
    tracked(folder.add({
      get ior() { const m = material(); return m.type === 'dielectric' ? m.ior : NEW_GLASS.ior; },
      set ior(v: number) { edit((m) => { if (m.type === 'dielectric') m.ior = v; }); },
    }, 'ior', MIN_IOR, MAX_IOR, 0.01));
  }
  addEmissionControls(folder, app, sphere, tracked);
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
