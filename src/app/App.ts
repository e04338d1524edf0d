/**
 * The page's state: the scene being edited, the selection, undo history, the
 * render resolution and the renderer. Edits mutate `scene` and re-upload it
 * (no shader recompile); each finished edit records the scene before it.
 */
import { PathTracer } from '../render/PathTracer';
import { mergeAssets, NO_ASSETS, type SceneAssets } from '../scene/assets';
import { SnapshotKeeper } from '../render/snapshot';
import { MAX_LIGHTS, MAX_SPHERES } from '../scene/limits';
import { cameraRay } from '../scene/camera';
import { pickObject, pickSurface, projectPoint, projectSphere, type MeshLookup, type ObjectHit, type ObjectKind } from '../scene/picking';
import type { Camera, Scene, Vec3 } from '../scene/types';
import { defaultMaterial } from '../materials/registry';
import { createLight, lightExtent, lightPosition, type Light, type LightType } from '../lights/registry';
import { History } from './history';
import { draggedLight, handleNear, handlePoints, markerNear, sunMarkers, type HandleDrag, type HandleKind } from './lightHandles';
import { LiveDenoiser } from './liveDenoise';
import { worldBoundingSphere } from './meshFit';
import { MeshUploads } from './meshUploads';
import { RenderLoop, type RenderStats, type ViewSettings } from './renderLoop';
import type { SavedState } from './savedState';

/** The panel's view settings: the render loop's, and whether the still image is denoised. */
export interface PageView extends ViewSettings {
  denoise: boolean;
}

/** A point in CSS pixels over the canvas (from its top left). */
export interface CanvasPoint {
  x: number;
  y: number;
}

/** The selected light's handles on screen, and where its aim line starts. */
export type ScreenHandles = Partial<Record<HandleKind | 'origin', CanvasPoint>>;

export interface Selection {
  kind: ObjectKind;
  index: number;
}

/** Most pixels rendered at full resolution (CSS size x devicePixelRatio is capped to this). */
const MAX_RENDER_PIXELS = 1_200_000;
/** How long after the last camera or object move the reduced resolution is kept. */
const SETTLE_MS = 250;
/** Linear scale of the render while something moves. */
const MOVING_SCALE = 0.5;

const clone = (scene: Scene): Scene => structuredClone(scene);

/** The least radius a selected light's handle shows (points and spots have none of their own). */
const LIGHT_HANDLE_RADIUS = 0.1;

export class App {
  scene: Scene;
  selection: Selection | null = null;
  readonly history = new History<Scene>();
  readonly view: PageView = { exposure: 0, toneMap: 'aces', paused: false, targetSpp: 0, denoise: false };
  readonly tracer: PathTracer;
  readonly loop: RenderLoop;
  /** Denoises the still image when view.denoise is on (liveDenoise.ts). */
  readonly denoiser: LiveDenoiser;
  /** Every map and model loaded this session (undo and redo may return to any scene that named one). */
  assets: SceneAssets = NO_ASSETS;
  /** A recent copy of the running sums: a lost context resumes from it. */
  readonly snapshots: SnapshotKeeper;
  /** The camera to return to with "reset view": the loaded scene's. */
  private homeCamera: Camera;
  private editBefore: Scene | null = null;
  private fullSize = { width: 1, height: 1 };
  private movingUntil = 0;
  private readonly listeners = new Set<() => void>();
  /** Uploads the scene, building a large mesh's BVH in a worker first (meshUploads.ts). */
  readonly meshUploads: MeshUploads;
  /** Reports a failure of a deferred upload (set by the page). */
  onUploadError: (message: string) => void = () => {};

  constructor(
    readonly canvas: HTMLCanvasElement,
    scene: Scene,
    private readonly maxWidth: number,
    onStats: (stats: RenderStats) => void,
    assets: SceneAssets = NO_ASSETS,
  ) {
    this.scene = clone(scene);
    this.assets = assets;
    this.homeCamera = structuredClone(scene.camera);
    // Meshes come with the first upload: their BVH is built in the worker, not while the page starts.
    this.tracer = new PathTracer(canvas, { ...this.scene, meshes: [] }, { width: 64, height: 48, assets });
    this.snapshots = new SnapshotKeeper(this.tracer);
    this.meshUploads = new MeshUploads(this.tracer, () => ({ scene: this.scene, assets: this.assets }), (m) => this.onUploadError(m));
    this.upload();
    this.denoiser = new LiveDenoiser(this.tracer, this.view, {
      moving: () => this.moving,
      stopped: () => this.view.paused || this.loop.done,
      redisplay: () => this.loop.invalidateDisplay(),
    });
    const beforeFrame = () => {
      this.applyResolution();
      this.snapshots.tick();
      this.denoiser.tick();
    };
    this.loop = new RenderLoop(this.tracer, this.view, beforeFrame, onStats);
  }

  /** The camera "reset view" goes back to. */
  get homeView(): Camera {
    return this.homeCamera;
  }

  /** Puts back an autosaved state: scene, home camera, view settings and undo history. */
  restore(state: SavedState): void {
    this.endEdit();
    this.homeCamera = structuredClone(state.homeCamera);
    Object.assign(this.view, state.view);
    this.history.replace(state.undo.map(clone), state.redo.map(clone));
    this.replaceScene(clone(state.scene));
    this.loop.invalidateDisplay();
    this.layout();
  }

  /** Called after every change of the scene or the selection (panel, overlay, buttons). */
  onChange(listener: () => void): void {
    this.listeners.add(listener);
  }

  changed(): void {
    this.listeners.forEach((listener) => listener());
  }

  get aspect(): number {
    return this.scene.image.width / this.scene.image.height;
  }

  // ------------------------------------------------------------ edits

  /** Starts (or continues) an edit: remembers the scene as it was before it. */
  beginEdit(): void {
    this.editBefore ??= clone(this.scene);
  }

  /** Finishes the current edit; records it for undo when it changed anything. */
  endEdit(): void {
    const before = this.closeEdit();
    if (before) this.history.record(before);
    this.changed();
  }

  /** Abandons the current edit (Escape during a drag): the scene goes back to how it was before it, and no undo step is recorded. */
  cancelEdit(): void {
    const before = this.closeEdit();
    if (before) this.replaceScene(before);
  }

  /** Closes the current edit: the scene before it when the edit changed anything, else null. */
  private closeEdit(): Scene | null {
    const before = this.editBefore;
    this.editBefore = null;
    return before && JSON.stringify(before) !== JSON.stringify(this.scene) ? before : null;
  }

  /** A continuous edit step (drag, slider): applies it now, recorded at endEdit. */
  live(mutate: (scene: Scene) => void, moving = false): void {
    this.beginEdit();
    mutate(this.scene);
    if (moving) this.movingUntil = performance.now() + SETTLE_MS;
    this.upload();
  }

  /** A discrete edit (button, key): applied and recorded at once. */
  edit(mutate: (scene: Scene) => void): void {
    this.live(mutate);
    this.endEdit();
  }

  undo(): void {
    this.endEdit();
    const previous = this.history.undo(clone(this.scene));
    if (previous) this.replaceScene(previous);
  }

  redo(): void {
    this.endEdit();
    const next = this.history.redo(clone(this.scene));
    if (next) this.replaceScene(next);
  }

  /** Loads a new scene (file, example, link): an undoable edit that also resets the home view. */
  load(scene: Scene, assets: SceneAssets = NO_ASSETS): void {
    this.endEdit();
    this.addAssets(assets);
    // Loading the scene already open (a reloaded link) adds no undo step.
    if (JSON.stringify(scene) !== JSON.stringify(this.scene)) this.history.record(clone(this.scene));
    this.homeCamera = structuredClone(scene.camera);
    this.replaceScene(clone(scene));
    this.layout();
  }

  resetView(): void {
    this.edit((s) => (s.camera = structuredClone(this.homeCamera)));
  }

  addSphere(): void {
    if (this.scene.spheres.length >= MAX_SPHERES) return;
    const { target } = this.scene.camera;
    const floor = this.scene.ground ? this.scene.ground.height : target[1] - 0.5;
    this.edit((s) =>
      s.spheres.push({ center: [target[0], floor + 0.5, target[2]], radius: 0.5, material: { ...defaultMaterial(), roughness: 0.5 } }),
    );
    this.select({ kind: 'sphere', index: this.scene.spheres.length - 1 });
  }

  addLight(type: LightType = 'sphere'): void {
    if (this.scene.lights.length >= MAX_LIGHTS) return;
    const { target } = this.scene.camera;
    this.edit((s) => s.lights.push(createLight(type, target)));
    this.select({ kind: 'light', index: this.scene.lights.length - 1 });
  }

  deleteSelection(): void {
    const selection = this.selection;
    if (!selection) return;
    this.selection = null;
    this.edit((s) => (selection.kind === 'sphere' ? s.spheres : selection.kind === 'mesh' ? s.meshes : s.lights).splice(selection.index, 1));
  }

  select(selection: Selection | null): void {
    this.selection = selection;
    this.changed();
  }

  /** The selected object's centre (a sphere's center, a light's or a mesh's position), live: moving it moves the object. */
  selectedCenter(): Vec3 | null {
    const s = this.selection;
    if (!s) return null;
    if (s.kind === 'mesh') return this.scene.meshes[s.index]?.position ?? null;
    if (s.kind === 'sphere') return this.scene.spheres[s.index]?.center ?? null;
    const light = this.scene.lights[s.index];
    return light ? lightPosition(light) : null;
  }

  selectedRadius(): number {
    const s = this.selection;
    if (!s) return 0;
    if (s.kind === 'sphere') return this.scene.spheres[s.index]?.radius ?? 0;
    const light = this.scene.lights[s.index];
    return light ? Math.max(lightExtent(light)?.radius ?? 0, LIGHT_HANDLE_RADIUS) : 0;
  }

  // ------------------------------------------------------------ picking

  /** Image coordinates (u right, v down) of a client point over the canvas. */
  imagePoint(clientX: number, clientY: number): { u: number; v: number } {
    const rect = this.canvas.getBoundingClientRect();
    return { u: (clientX - rect.left) / rect.width, v: (clientY - rect.top) / rect.height };
  }

  rayAt(clientX: number, clientY: number) {
    const { u, v } = this.imagePoint(clientX, clientY);
    return cameraRay(this.scene.camera, this.aspect, u, v);
  }

  pick(clientX: number, clientY: number): ObjectHit | null {
    return pickObject(this.scene, this.rayAt(clientX, clientY), this.meshLookup);
  }

  /** The decoded triangles of a file the scene names. */
  readonly meshLookup: MeshLookup = (file) => this.assets.meshes.get(file);

  /** The selected object's bounding sphere (a mesh's from its bounds), for the outline. */
  private selectedSphere(): { center: Vec3; radius: number } | null {
    const s = this.selection;
    const mesh = s?.kind === 'mesh' ? this.scene.meshes[s.index] : undefined;
    const data = mesh && this.assets.meshes.get(mesh.file);
    if (mesh && data) return worldBoundingSphere(mesh, data);
    const center = this.selectedCenter();
    return center && s?.kind !== 'mesh' ? { center, radius: this.selectedRadius() } : null;
  }

  /** Focuses the thin lens on the surface under a client point. */
  focusAt(clientX: number, clientY: number): void {
    const ray = this.rayAt(clientX, clientY);
    const hit = pickSurface(this.scene, ray, this.meshLookup);
    if (!hit) return;
    const { position, target } = this.scene.camera;
    const forward = [0, 1, 2].map((i) => target[i] - position[i]);
    const norm = Math.hypot(forward[0], forward[1], forward[2]);
    // The plane in focus is perpendicular to the view: distance along the view axis.
    const depth = (hit.t * (ray.direction[0] * forward[0] + ray.direction[1] * forward[1] + ray.direction[2] * forward[2])) / norm;
    if (depth > 0) this.edit((s) => (s.camera.focusDistance = Math.min(depth, 1e7)));
  }

  /** The selection outline in CSS pixels over the canvas, or null. */
  selectionOutline(): { x: number; y: number; r: number } | null {
    const sphere = this.selectedSphere();
    if (!sphere) return null;
    const outline = projectSphere(this.scene.camera, this.aspect, sphere.center, sphere.radius);
    if (!outline) return null;
    const width = this.canvas.clientWidth;
    const height = this.canvas.clientHeight;
    return { x: outline.u * width, y: outline.v * height, r: outline.radius * height };
  }

  // ------------------------------------------------------------ light handles

  /** The selected light, when the selection is one. */
  selectedLight(): Light | null {
    const s = this.selection;
    return s?.kind === 'light' ? (this.scene.lights[s.index] ?? null) : null;
  }

  /** The selected light's handles in CSS pixels over the canvas (those in front of the camera), or null. */
  lightHandles(): ScreenHandles | null {
    const light = this.selectedLight();
    if (!light) return null;
    const points = handlePoints(light, this.scene.camera);
    const rect = this.canvas.getBoundingClientRect();
    const screen = (p: Vec3 | null) => (p ? this.canvasPointOf(p, rect) : undefined);
    return { move: screen(points.move), aim: screen(points.aim), origin: screen(points.origin) };
  }

  /** Where a world point is seen, in CSS pixels over the canvas (`rect`: its box), or undefined behind the camera. */
  private canvasPointOf(p: Vec3, rect: DOMRect): CanvasPoint | undefined {
    const projected = projectPoint(this.scene.camera, this.aspect, p);
    return projected ? { x: projected.u * rect.width, y: projected.v * rect.height } : undefined;
  }

  /** Every directional light's marker (its "sun") in CSS pixels over the canvas, those in front of the camera. */
  sunMarkers(): (CanvasPoint & { index: number })[] {
    const rect = this.canvas.getBoundingClientRect();
    return sunMarkers(this.scene.lights, this.scene.camera).flatMap(({ index, point }) => {
      const at = this.canvasPointOf(point, rect);
      return at ? [{ index, ...at }] : [];
    });
  }

  /** The index of the directional light whose marker is within `radius` CSS pixels of a client point, or null. */
  sunMarkerAt(clientX: number, clientY: number, radius: number): number | null {
    const rect = this.canvas.getBoundingClientRect();
    return markerNear(this.sunMarkers(), clientX - rect.left, clientY - rect.top, radius);
  }

  /** The selected light's handle within `radius` CSS pixels of a client point, or null. */
  handleAt(clientX: number, clientY: number, radius: number): HandleKind | null {
    const handles = this.lightHandles();
    if (!handles) return null;
    const rect = this.canvas.getBoundingClientRect();
    return handleNear(handles, clientX - rect.left, clientY - rect.top, radius);
  }

  /** Starts dragging one of the selected light's handles (the edit is recorded at endEdit). */
  beginHandleDrag(kind: HandleKind, clientX: number, clientY: number): HandleDrag | null {
    const light = this.selectedLight();
    if (!light || !this.selection) return null;
    this.beginEdit();
    return { kind, index: this.selection.index, light: structuredClone(light), camera: structuredClone(this.scene.camera), start: this.rayAt(clientX, clientY) };
  }

  /** Moves a dragged handle to a client point: a live edit of the light's keys (no recompile). */
  dragHandle(drag: HandleDrag, clientX: number, clientY: number): void {
    const light = this.scene.lights[drag.index];
    // The light was deselected or replaced (undo) during the drag: leave it.
    if (!light || this.selection?.kind !== 'light' || this.selection.index !== drag.index || light.type !== drag.light.type) return;
    const ray = this.rayAt(clientX, clientY);
    // The aim follows visible surfaces, not the lights' own pick spheres.
    const surface = drag.kind === 'aim' ? (pickSurface({ ...this.scene, lights: [] }, ray, this.meshLookup)?.point ?? null) : null;
    const keys = draggedLight(drag, ray, surface);
    if (keys) this.live(() => Object.assign(light, keys), true);
  }

  // ------------------------------------------------------------ resolution

  /** Fits the canvas box to its container at the scene's aspect ratio; sets the full render size. */
  layout(): void {
    const box = this.canvas.parentElement!;
    const area = box.parentElement!;
    const availableWidth = Math.max(1, area.clientWidth);
    const availableHeight = Math.max(1, area.clientHeight);
    const aspect = this.aspect;
    const cssWidth = Math.min(availableWidth, availableHeight * aspect);
    const cssHeight = cssWidth / aspect;
    box.style.width = `${Math.floor(cssWidth)}px`;
    box.style.height = `${Math.floor(cssHeight)}px`;
    let width = cssWidth * (window.devicePixelRatio || 1);
    width = Math.min(width, this.maxWidth, Math.sqrt(MAX_RENDER_PIXELS * aspect));
    this.fullSize = { width: Math.max(8, Math.round(width)), height: Math.max(8, Math.round(width / aspect)) };
    this.changed();
  }

  /** Before each frame: reduced resolution while something moves, full when it stops. */
  private applyResolution(): void {
    const scale = this.moving ? MOVING_SCALE : 1;
    const width = Math.max(8, Math.round(this.fullSize.width * scale));
    const height = Math.max(8, Math.round(this.fullSize.height * scale));
    if (width !== this.tracer.width || height !== this.tracer.height) this.tracer.setSize(width, height);
  }

  /** True while the camera or an object moves (and shortly after): rendered at reduced resolution. */
  get moving(): boolean {
    return performance.now() < this.movingUntil;
  }

  /** Marks the view as moving (wheel, drag) so the loop renders at reduced resolution. */
  markMoving(): void {
    this.movingUntil = performance.now() + SETTLE_MS;
  }

  private replaceScene(scene: Scene): void {
    this.scene = scene;
    const s = this.selection;
    if (s && !(s.kind === 'sphere' ? scene.spheres : s.kind === 'mesh' ? scene.meshes : scene.lights)[s.index]) this.selection = null;
    this.upload();
    this.changed();
  }

  /** Adds decoded files (maps, models, texture images) to those the scenes of this session may use. */
  addAssets(assets: SceneAssets): void {
    this.assets = mergeAssets(this.assets, assets);
  }

  private upload(): void {
    this.meshUploads.upload();
  }
}
