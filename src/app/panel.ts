/**
 * The control panel (lil-gui). Every control reads and writes the scene
 * through accessors, so `refresh()` after undo, load or a drag shows the
 * current values. Scene colors are linear; the pickers show sRGB hex.
 */
import GUI, { type Controller } from 'lil-gui';
import { TONEMAPS } from '../render/toneMaps';
import { hexToLinear, linearToHex } from '../scene/color';
import { MAX_BOUNCES } from '../scene/limits';
import { defaultMaterial, mainColorKey, materialControls } from '../materials/registry';
import { lightControls } from '../lights/registry';
import type { LightControl } from '../lights/kind';
import type { Ground, Vec3 } from '../scene/types';
import type { App } from './App';
import { addMaterialInput, addSphereMaterialControls, materialLayoutKey } from './materialControls';
import { addMeshControls } from './meshControls';
import { addEnvironmentControls } from './environmentControls';
import type { EnvironmentMaps } from './environmentMaps';
import type { TextureImages } from './textureImages';
import { objectLabel, objectOfKey, sceneObjects, selectionKey } from './sceneObjects';

const DEFAULT_GROUND: Ground = { height: 0, material: defaultMaterial() };

export class Panel {
  readonly gui: GUI;
  private selectionFolder: GUI;
  private selectionKey = '';
  /** The selection folder's first row: every object of the scene, to select one without a pointer (kept when the folder is rebuilt). */
  private objectList: Controller;
  private objectListKey = '';
  private lastGround: Ground = structuredClone(DEFAULT_GROUND);
  private groundFolder: GUI | null = null;
  private groundControls: Controller[] = [];
  private groundLayout = '';

  constructor(
    private readonly app: App,
    container: HTMLElement,
    maps: EnvironmentMaps | null = null,
    /** The meshes' texture slots (absent: no slots). */
    private readonly images: TextureImages | null = null,
  ) {
    this.gui = new GUI({ container, title: 'Controls' });
    this.selectionFolder = this.gui.addFolder('Selection');
    this.objectList = this.addObjectList(this.selectionFolder);
    this.refreshObjectList();
    this.buildSelection();
    addEnvironmentControls(this.gui, app, maps, (c) => this.tracked(c)).close();
    this.buildGround();
    this.buildCamera();
    this.buildRender();
    for (const folder of [this.gui, ...this.gui.foldersRecursive()]) openWithoutAnimation(folder);
    app.onChange(() => this.refresh());
  }

  /** Shows the scene's current values (after undo, load, drags...). */
  refresh(): void {
    this.refreshObjectList();
    if (this.currentSelectionKey() !== this.selectionKey) this.buildSelection();
    const ground = this.app.scene.ground ?? this.lastGround;
    if (this.groundFolder && materialLayoutKey(ground.material) !== this.groundLayout) this.buildGroundMaterial(this.groundFolder);
    for (const controller of this.gui.controllersRecursive()) controller.updateDisplay();
  }

  /**
   * What the selection folder was built for: the object, its name (a light's
   * kind, a mesh's file: an undo or a load may put another there) and its
   * material's layout (its type's controls, the inputs that are textures).
   */
  private currentSelectionKey(): string {
    const s = this.app.selection;
    if (!s) return '';
    const material = s.kind === 'light' ? undefined : (s.kind === 'sphere' ? this.app.scene.spheres : this.app.scene.meshes)[s.index]?.material;
    return `${selectionKey(s)}:${objectLabel(this.app.scene, s)}:${material ? materialLayoutKey(material) : ''}`;
  }

  /**
   * The object list: choosing an entry selects it as a click on it does
   * (app.select: the same handles, the same folder); it shows the selection
   * however it was made. A native select, so the keyboard works it (arrows
   * pick, and attachKeys takes Delete and Escape there: data-shortcuts).
   */
  private addObjectList(folder: GUI): Controller {
    const app = this.app;
    const list = folder.add({
      get object() { return selectionKey(app.selection); },
      set object(key: string) { app.select(objectOfKey(app.scene, key)); },
    }, 'object', { none: '' });
    list.domElement.querySelector('select')!.dataset.shortcuts = '';
    return list;
  }

  /** Lists the scene's objects again when they changed (added, removed, undone, loaded); keeps the element, so its focus. */
  private refreshObjectList(): void {
    const objects = sceneObjects(this.app.scene);
    const key = objects.map((o) => o.label).join('\n');
    if (key === this.objectListKey) return;
    this.objectListKey = key;
    this.objectList.options({ none: '', ...Object.fromEntries(objects.map((o) => [o.label, o.key])) });
  }

  /** Wires a controller's changes into the edit history. */
  private tracked<T extends Controller>(controller: T): T {
    controller.onFinishChange(() => this.app.endEdit());
    return controller;
  }

  private buildSelection(): void {
    const app = this.app;
    const folder = this.selectionFolder;
    for (const c of [...folder.controllers]) if (c !== this.objectList) c.destroy();
    const s = app.selection;
    this.selectionKey = this.currentSelectionKey();
    folder.title(s ? `Selected ${objectLabel(app.scene, s) ?? `${s.kind} ${s.index + 1}`}` : 'Selection (click an object)');
    if (!s) return;
    const sphere = () => app.scene.spheres[s.index];
    const light = () => app.scene.lights[s.index];
    const edit = (f: () => void) => app.live(f);
    if (s.kind === 'mesh') {
      const slots = this.images?.slotsFor((scene) => scene.meshes[s.index]?.material ?? undefined);
      addMeshControls(folder, app, () => app.scene.meshes[s.index], (c) => this.tracked(c), slots);
    } else if (s.kind === 'sphere') {
      addSphereMaterialControls(folder, app, sphere, (c) => this.tracked(c));
      this.tracked(folder.add({
        get radius() { return sphere().radius; },
        set radius(v: number) { edit(() => (sphere().radius = v)); },
      }, 'radius', 0.01, 10, 0.01));
    } else {
      for (const c of lightControls(light())) this.addLightControl(folder, c, () => light() as unknown as Record<string, unknown>);
    }
    folder.add({ remove: () => app.deleteSelection() }, 'remove').name('Delete');
    folder.open();
  }

  /** One of a light kind's controls (src/lights/<kind>/kind.ts), editing the selected light live (no recompile). */
  private addLightControl(folder: GUI, c: LightControl, light: () => Record<string, unknown>): void {
    const edit = (f: () => void) => this.app.live(f);
    if (c.control === 'color') {
      this.tracked(folder.addColor({
        get value() { return linearToHex(light()[c.key] as Vec3); },
        set value(v: string) { edit(() => (light()[c.key] = hexToLinear(v))); },
      }, 'value').name(c.label));
    } else if (c.control === 'number') {
      this.tracked(folder.add({
        get value() { return light()[c.key] as number; },
        set value(v: number) { edit(() => (light()[c.key] = v)); },
      }, 'value', c.min, c.max, c.step).name(c.label));
    } else {
      // A vector: one field per component.
      const size = (light()[c.key] as number[]).length;
      for (let k = 0; k < size; k++) {
        this.tracked(folder.add({
          get value() { return (light()[c.key] as number[])[k]; },
          set value(v: number) { edit(() => ((light()[c.key] as number[])[k] = v)); },
        }, 'value').name(`${c.label} ${'xyz'[k]}`));
      }
    }
  }

  /**
   * The ground's material: its main color (mainColorKey) and roughness
   * (every kind has them), as its kind's controls (texture slots included:
   * the ground has coordinates) under the labels "color" and "roughness";
   * no emission (the format forbids it there). Rebuilt when the material's
   * layout changes (its kind, which inputs are textures).
   */
  private buildGroundMaterial(folder: GUI): void {
    const app = this.app;
    for (const c of this.groundControls) c.destroy();
    const owner = () => app.scene.ground ?? this.lastGround;
    const material = owner().material;
    this.groundLayout = materialLayoutKey(material);
    const slots = this.images?.slotsFor((scene) => scene.ground?.material);
    const controls = materialControls(material);
    const inputs: [string, string][] = [[mainColorKey(material), 'color'], ['roughness', 'roughness']];
    this.groundControls = inputs.flatMap(([key, label]) => {
      const control = controls.find((c) => c.key === key);
      const controller = control && addMaterialInput(folder, app, { ...control, label }, owner, (c) => this.tracked(c), slots);
      return controller ? [controller] : [];
    });
  }

  private buildGround(): void {
    const app = this.app;
    const folder = this.gui.addFolder('Ground');
    const ground = () => (app.scene.ground ??= structuredClone(this.lastGround));
    const panel = this;
    this.tracked(folder.add({
      get enabled() { return app.scene.ground !== null; },
      set enabled(on: boolean) {
        app.live((s) => {
          if (s.ground) panel.lastGround = structuredClone(s.ground);
          s.ground = on ? structuredClone(panel.lastGround) : null;
        });
      },
    }, 'enabled'));
    this.tracked(folder.add({
      get height() { return app.scene.ground?.height ?? panel.lastGround.height; },
      set height(v: number) { app.live(() => (ground().height = v)); },
    }, 'height', -5, 5, 0.01));
    this.groundFolder = folder;
    this.buildGroundMaterial(folder);
    folder.close();
  }

  private buildCamera(): void {
    const app = this.app;
    const folder = this.gui.addFolder('Camera');
    const camera = () => app.scene.camera;
    const distance = () => Math.hypot(...([0, 1, 2].map((i) => camera().target[i] - camera().position[i]) as [number, number, number]));
    this.tracked(folder.add({
      get fov() { return camera().fov; },
      set fov(v: number) { app.live(() => (camera().fov = v)); },
    }, 'fov', 5, 120, 0.5).name('fov (deg)'));
    this.tracked(folder.add({
      get aperture() { return camera().aperture; },
      set aperture(v: number) { app.live(() => (camera().aperture = v)); },
    }, 'aperture', 0, 1, 0.005).name('aperture radius'));
    this.tracked(folder.add({
      get focus() { return camera().focusDistance ?? distance(); },
      set focus(v: number) { app.live(() => (camera().focusDistance = v)); },
    }, 'focus', 0.05, 50, 0.01).name('focus distance'));
    folder.add({ reset: () => app.resetView() }, 'reset').name('Reset view');
    folder.close();
  }

  private buildRender(): void {
    const app = this.app;
    const view = app.view;
    const folder = this.gui.addFolder('Render');
    this.tracked(folder.add({
      get bounces() { return app.scene.render.maxBounces; },
      set bounces(v: number) { app.live(() => (app.scene.render.maxBounces = v)); },
    }, 'bounces', 0, MAX_BOUNCES, 1).name('max bounces'));
    const redisplay = () => app.loop.invalidateDisplay();
    // View settings are not scene edits (no undo step) but are saved with it: announce them.
    const saved = () => app.changed();
    folder.add(view, 'exposure', -6, 6, 0.1).name('exposure (stops)').onChange(redisplay).onFinishChange(saved);
    folder.add(view, 'toneMap', [...TONEMAPS]).name('tone map').onChange(redisplay).onFinishChange(saved);
    folder.add(view, 'targetSpp', 0, 100000, 1).name('stop at spp (0 = never)').onFinishChange(saved);
    folder.add(view, 'paused').name('paused');
    // Followed by app.denoiser each frame; a denoiser that cannot start turns it off again.
    folder.add(view, 'denoise').name('denoise (still view)').onFinishChange(saved);
    folder.open();
  }
}

/**
 * lil-gui animates folders with two nested animation frames and a
 * transitionend; when frames are slow (a long path-tracing frame) the
 * transition can end before the height is set, leaving the folder stuck at a
 * fixed height that clips later controls. Open and close without animation.
 */
function openWithoutAnimation(folder: GUI): void {
  folder.$title.addEventListener(
    'click',
    (event) => {
      event.stopImmediatePropagation();
      folder.open(folder._closed);
    },
    { capture: true },
  );
}
