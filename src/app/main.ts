/**
 * The interactive page: wires the renderer, input, panel, files and
 * statistics together. Untrusted text (files, links, error logs) is only
 * ever shown through textContent.
 */
import './style.css';
import { ShaderCompileError } from '../render/gl/program';
import { WebGLUnavailableError } from '../render/gl/context';
import { safeParseScene } from '../scene/schema';
import { defaultScene, PRESET_NAMES, PRESETS } from '../scene/presets';
import { stringifyScene } from '../scene/serialize';
import { App } from './App';
import { downloadBlob, readSceneFile, rgba8ToPngBlob, sceneFromHash, shareHash } from './files';
import { attachInput, attachKeys } from './input';
import { clearError, notify, showError, showFatal, showIssues } from './messages';
import { Autosave, readStartState, type SaveStatus, type StartState } from './persistence';
import { linkDigest } from './savedState';
import { SceneLoader } from './sceneLoader';
import { addModelFile, isModelFile, meshExampleFiles, showMeshWarnings } from './meshControls';
import { userFiles } from './userFiles';
import { droppedFiles } from './droppedFiles';
import { EnvironmentMaps, MAP_FILE_PATTERN } from './environmentMaps';
import { MAP_EXAMPLES, MESH_EXAMPLES, TEXTURE_EXAMPLES } from './examples';
import { Panel } from './panel';
import { TextureImages } from './textureImages';
import { objectLabel } from './sceneObjects';
import { LIGHT_TYPE_NAMES, lightLabel, type LightType } from '../lights/registry';
import { encodePfm } from '../image/pfm';
import type { RenderStats } from './renderLoop';
import type { DenoiseState } from './liveDenoise';

const $ = <T extends HTMLElement = HTMLElement>(id: string) => document.getElementById(id) as T;
const SVG_NS = 'http://www.w3.org/2000/svg';

// ---------------------------------------------------------------- start

const DEFAULT_VIEW = { exposure: 0, toneMap: 'aces', targetSpp: 0 } as const;

function maxRenderWidth(): number {
  const value = Number(new URLSearchParams(location.search).get('maxwidth'));
  return Number.isFinite(value) && value >= 8 ? value : Infinity;
}

async function start(): Promise<void> {
  const canvas = $<HTMLCanvasElement>('viewport');
  performance.mark('script-start');
  const startState = await readStartState(location.hash);
  performance.mark('state-read');
  let app: App;
  try {
    app = new App(canvas, startState.saved?.scene ?? defaultScene(), maxRenderWidth(), showStats, startState.assets);
  } catch (error) {
    if (error instanceof WebGLUnavailableError) {
      showFatal('WebGL2 is not available', `${error.message} Try a current Chrome, Edge, Firefox or Safari with hardware acceleration on.`);
    } else if (error instanceof ShaderCompileError) {
      showFatal('The path tracing shader failed to compile', `The ${error.stage} stage reported:`, error.log);
    } else {
      showFatal('The renderer could not start', (error as Error).message ?? String(error));
    }
    return;
  }
  performance.mark('renderer-ready');
  const autosave = new Autosave(app, showSaveStatus);
  const maps = new EnvironmentMaps(app, autosave, showIssues, clearError);
  const images = new TextureImages(app, autosave, showError);
  const panel = new Panel(app, $('panel'), maps, images);
  app.onUploadError = (message) => showError(message);
  wireDenoiser(app);
  const loader = openStartState(app, autosave, startState);
  attachKeys(app, attachInput(app, canvas));
  wireToolbar(app, loader);
  wireFiles(app, autosave, loader, maps);
  wireContextLoss(app);
  wireOverlay(app);
  if (window.matchMedia('(max-width: 760px)').matches) panel.gui.close();
  new ResizeObserver(() => app.layout()).observe($('viewport-area'));
  app.layout();
  app.loop.start();
  autosave.start();
  document.body.dataset.state = 'ready';
}

/** Restores the saved work, then opens the link's scene over it (one Undo brings the saved one back). */
function openStartState(app: App, autosave: Autosave, start: StartState): SceneLoader {
  if (start.saved) {
    app.restore(start.saved);
    autosave.assets = start.saved.assets;
  }
  autosave.linkDigest = start.linkDigest;
  const loader = new SceneLoader(
    (scene, assets, files) => {
      clearError();
      app.load(scene, assets);
      showMeshWarnings(scene, assets);
      if (files.size) void autosave.keepFiles(scene, files);
    },
    showIssues,
    () => app.assets,
  );
  if (start.linkScene) {
    const scene = start.linkScene;
    void loader.open('The scene in this link', () => ({ ok: true, scene }));
  }
  if (start.linkResult && !start.linkResult.ok) showIssues('The scene in this link', start.linkResult.issues);
  if (start.notices.length) notify(start.notices.join(' '), 8000);
  return loader;
}

function showSaveStatus(status: SaveStatus, detail: string): void {
  const element = $('saved');
  element.textContent = status === 'pending' ? 'saving…' : status === 'idle' ? '' : detail;
  element.title = status === 'failed' ? 'Your changes are not saved in this browser: save the scene as JSON to keep it.' : '';
  element.classList.toggle('warn', status === 'failed');
  document.body.dataset.saved = status;
}

// ---------------------------------------------------------------- statistics

/**
 * Sets an element's text only when it changes: every frame calls showStats,
 * and a write, even of the same text, makes the page lay out and repaint
 * (a frame's worth of work with a software GPU).
 */
function showText(id: string, text: string): void {
  const element = $(id);
  if (element.textContent !== text) element.textContent = text;
}

let firstPixelShown = false;
function showStats(stats: RenderStats): void {
  if (!firstPixelShown && stats.spp > 0) {
    // Time to first pixel, from navigation start: the bench reads it (bench/first-pixel.ts).
    firstPixelShown = true;
    document.body.dataset.firstPixelMs = performance.mark('first-pixel').startTime.toFixed(0);
  }
  showText('spp', String(stats.spp));
  showText('rate', `${stats.sppPerSecond.toFixed(stats.sppPerSecond < 10 ? 1 : 0)} spp/s`);
  showText('elapsed', `${(stats.elapsedMs / 1000).toFixed(1)} s`);
  showText('resolution', `${stats.width}×${stats.height}`);
  showText('state', stats.state === 'rendering' ? '' : stats.state);
  document.body.dataset.render = stats.state;
  // For tests and benchmarks: the work per frame the render loop chose, and samples with the one in progress.
  document.body.dataset.pathsPerFrame = String(Math.round(stats.pathsPerFrame));
  document.body.dataset.samples = (stats.spp + stats.sampleProgress).toFixed(3);
}

// ---------------------------------------------------------------- denoiser

function wireDenoiser(app: App): void {
  app.denoiser.onState = showDenoiseState;
  app.denoiser.onFailure = (message) => {
    // The toggle is already off again; the scene and its samples are untouched.
    showError('Denoising is not available in this browser; the raw image is shown.', [message]);
    app.changed();
  };
}

function showDenoiseState(state: DenoiseState): void {
  const status = $('denoise-status');
  status.textContent = state.text;
  status.title = state.text;
  document.body.dataset.shown = state.shown;
}

// ---------------------------------------------------------------- toolbar

function wireToolbar(app: App, loader: SceneLoader): void {
  const click = (id: string, action: () => void) => $(id).addEventListener('click', action);
  click('new-scene', () => {
    void loader.open('The example scene', () => ({ ok: true, scene: defaultScene() })).then((opened) => {
      if (!opened) return;
      Object.assign(app.view, DEFAULT_VIEW);
      app.loop.invalidateDisplay();
      app.changed();
      notify('New scene: the example. Undo brings your previous scene back.');
    });
  });
  click('add-sphere', () => app.addSphere());
  // "+ Light" adds a light of the kind chosen beside it (a sphere unless changed).
  const lightKind = $<HTMLSelectElement>('light-kind');
  for (const type of LIGHT_TYPE_NAMES) lightKind.add(new Option(lightLabel(type), type));
  click('add-light', () => app.addLight(lightKind.value as LightType));
  click('delete', () => app.deleteSelection());
  click('undo', () => app.undo());
  click('redo', () => app.redo());
  click('reset-view', () => app.resetView());
  click('pause', () => {
    app.view.paused = !app.view.paused;
    app.changed();
  });
  const update = () => {
    $<HTMLButtonElement>('undo').disabled = !app.history.canUndo;
    $<HTMLButtonElement>('redo').disabled = !app.history.canRedo;
    $<HTMLButtonElement>('delete').disabled = !app.selection;
    $('pause').textContent = app.view.paused ? 'Resume' : 'Pause';
  };
  app.onChange(update);
  update();
}

// ---------------------------------------------------------------- files

function wireFiles(app: App, autosave: Autosave, loader: SceneLoader, maps: EnvironmentMaps): void {
  // A scene file with the maps and models it names, opened or dropped together;
  // a map file alone becomes the environment of the current scene.
  const openFiles = (list: Iterable<File> | undefined | null) => {
    const files = [...(list ?? [])];
    if (!files.length) return;
    if (files.length === 1 && MAP_FILE_PATTERN.test(files[0].name)) {
      void maps.useFile(files[0]);
      return;
    }
    const models = files.filter((f) => isModelFile(f.name));
    if (models.length > 0 && !files.some((f) => /\.json$/i.test(f.name))) {
      // Models without a scene are added to the open scene, one after another;
      // the other files are what they read beside them (a .gltf's .bin and images, an OBJ's .mtl).
      const companions = new Map(files.filter((f) => !models.includes(f)).map((f) => [f.name, f] as const));
      const keep = (kept: ReadonlyMap<string, Blob>) => void autosave.keepFiles(app.scene, kept);
      void models.reduce<Promise<unknown>>((done, f) => done.then(() => addModelFile(app, f, keep, companions)), Promise.resolve());
      return;
    }
    const scene = files.find((f) => /\.json$/i.test(f.name)) ?? (files.length === 1 ? files[0] : undefined);
    if (!scene) {
      showIssues('These files', [{ path: '', message: 'none of them is a scene (.json): open the scene file together with its maps and models' }]);
      return;
    }
    const companions = new Map(files.filter((f) => f !== scene).map((f) => [f.name, f] as const));
    void loader.open(`"${scene.name}"`, () => readSceneFile(scene), companions);
  };

  const input = $<HTMLInputElement>('file');
  $('open').addEventListener('click', () => input.click());
  input.addEventListener('change', () => {
    const files = [...(input.files ?? [])];
    input.value = '';
    openFiles(files);
  });

  const hint = $('drop-hint');
  window.addEventListener('dragover', (event) => {
    if (!event.dataTransfer?.types.includes('Files')) return;
    event.preventDefault();
    hint.hidden = false;
  });
  window.addEventListener('dragleave', (event) => {
    if (event.relatedTarget === null) hint.hidden = true;
  });
  window.addEventListener('drop', (event) => {
    hint.hidden = true;
    if (event.defaultPrevented) return; // taken on its way here (an image dropped on a texture slot)
    event.preventDefault();
    // A dropped folder's files (a .gltf with its .bin and images) as if dropped together.
    void droppedFiles(event.dataTransfer).then(openFiles);
  });

  const examples = $<HTMLSelectElement>('examples');
  const exampleScenes: Record<string, unknown> = Object.fromEntries([...PRESET_NAMES.map((n) => [n, PRESETS[n]] as const), ...Object.entries(MAP_EXAMPLES)]);
  for (const name of Object.keys(exampleScenes)) {
    const option = document.createElement('option');
    option.value = name;
    option.textContent = name;
    examples.append(option);
  }
  for (const name of [...Object.keys(MESH_EXAMPLES), ...Object.keys(TEXTURE_EXAMPLES)]) examples.append(new Option(name, name));
  examples.addEventListener('change', () => {
    const name = examples.value;
    examples.value = '';
    if (Object.hasOwn(exampleScenes, name)) void loader.open(`The example "${name}"`, () => safeParseScene(exampleScenes[name]));
    if (Object.hasOwn(MESH_EXAMPLES, name)) void meshExampleFiles().then((files) => loader.open(`The example "${name}"`, () => safeParseScene(MESH_EXAMPLES[name]), files));
    if (Object.hasOwn(TEXTURE_EXAMPLES, name)) {
      const example = TEXTURE_EXAMPLES[name];
      void example.files().then((files) => loader.open(`The example "${name}"`, () => safeParseScene(example.scene), files));
    }
  });

  $('save-json').addEventListener('click', () => {
    downloadBlob(new Blob([stringifyScene(app.scene) + '\n'], { type: 'application/json' }), 'scene.json');
  });

  $('share').addEventListener('click', () => {
    const hash = shareHash(app.scene);
    history.replaceState(null, '', hash);
    autosave.linkDigest = linkDigest(hash); // reloading this address keeps later edits
    autosave.schedule();
    const url = location.href;
    // A user's files (maps, models, texture images) cannot travel in a link: say so where the link is made.
    const own = userFiles(app.scene, app.assets).map((file) => `"${file}"`);
    const ownMap = own.length > 0 ? ` It names your ${own.length > 1 ? 'files' : 'file'} ${own.join(', ')}, which a link cannot carry: whoever opens it must open ${own.length > 1 ? 'those files' : 'that file'} too.` : '';
    navigator.clipboard?.writeText(url).then(
      () => notify(`Link copied: it carries the whole scene.${ownMap}`, ownMap ? 8000 : undefined),
      () => notify(`The page address now carries the scene: copy it from the address bar.${ownMap}`, ownMap ? 8000 : undefined),
    );
  });

  window.addEventListener('hashchange', () => {
    const hash = location.hash;
    const result = sceneFromHash(hash);
    if (!result) return;
    void loader.open('The scene in this link', () => result).then((opened) => {
      if (opened) autosave.linkDigest = linkDigest(hash);
    });
  });

  const whenRendering = (action: () => Promise<void> | void) => async () => {
    if (app.tracer.contextLost) {
      showError('The image is not available while the WebGL context is being restored.');
      return;
    }
    try {
      await action();
    } catch (error) {
      showError('Saving the image failed.', [(error as Error).message]);
    }
  };
  $('save-png').addEventListener('click', whenRendering(async () => {
    const { width, height } = app.tracer;
    const pixels = app.tracer.readDisplayed({ exposure: app.view.exposure, toneMap: app.view.toneMap });
    downloadBlob(await rgba8ToPngBlob(width, height, pixels), 'pathtrace.png');
  }));
  $('save-pfm').addEventListener('click', whenRendering(() => {
    const { width, height } = app.tracer;
    const bytes = encodePfm(width, height, app.denoiser.shownLinear ?? app.tracer.readLinear());
    downloadBlob(new Blob([bytes], { type: 'application/octet-stream' }), 'pathtrace.pfm');
  }));
}

// ---------------------------------------------------------------- context loss

function wireContextLoss(app: App): void {
  const loseContext = app.tracer.gl.getExtension('WEBGL_lose_context');
  app.tracer.on('contextlost', () => {
    notify('The WebGL context was lost; restoring it…');
    // The browser restores real losses by itself; a simulated one
    // (WEBGL_lose_context) is restored here if the browser has not done it.
    window.setTimeout(() => {
      if (app.tracer.contextLost && app.tracer.gl.isContextLost()) loseContext?.restoreContext();
    }, 1000);
  });
  document.addEventListener('visibilitychange', () => {
    if (document.visibilityState === 'hidden') app.snapshots.captureNow();
  });
  app.tracer.on('contextrestored', () => {
    // The snapshot keeper (created with the App, so called first) has put back what it kept.
    const kept = app.tracer.sampleCount;
    notify(`The WebGL context was restored; ${kept > 0 ? `the image resumes from ${kept} spp` : 'rendering starts again'}.`);
    app.changed();
  });
}

// ---------------------------------------------------------------- selection outline and light handles

function wireOverlay(app: App): void {
  const svg = $('overlay') as unknown as SVGSVGElement;
  // Drawn for the pointer only (the panel's object list names the selection): hidden from assistive technology.
  const element = (tag: string, className: string, testId?: string) => {
    const e = document.createElementNS(SVG_NS, tag);
    e.setAttribute('class', className);
    e.setAttribute('aria-hidden', 'true');
    if (testId) e.dataset.testid = testId;
    return e;
  };
  const dark = element('circle', 'outline-dark');
  const light = element('circle', 'outline');
  // The selected light's aim line and handles (lightHandles.ts): drawn here, dragged through the canvas's input.
  const aimLineDark = element('line', 'aim-line-dark');
  const aimLine = element('line', 'aim-line');
  const moveHandle = element('circle', 'handle handle-move', 'move-handle');
  const aimHandle = element('circle', 'handle handle-aim', 'aim-handle');
  svg.append(dark, light, aimLineDark, aimLine, moveHandle, aimHandle);
  const drawSuns = sunMarkerLayer(svg, dark, (index) => app.select({ kind: 'light', index }), (index) => objectLabel(app.scene, { kind: 'light', index }) ?? '');
  // draw() runs every frame: it writes only what changed (setIfChanged).
  const place = (circle: Element, at: { x: number; y: number } | undefined, r: number) => {
    setIfChanged(circle, 'display', at ? 'inline' : 'none');
    if (!at) return;
    setIfChanged(circle, 'cx', at.x.toFixed(1));
    setIfChanged(circle, 'cy', at.y.toFixed(1));
    setIfChanged(circle, 'r', String(r));
  };
  const draw = () => {
    const outline = app.selectionOutline();
    const handles = app.lightHandles();
    const suns = app.sunMarkers();
    const shown = outline || handles || suns.length ? '' : 'none';
    if (svg.style.display !== shown) svg.style.display = shown;
    drawSuns(suns);
    for (const circle of [dark, light]) place(circle, outline ? { x: outline.x, y: outline.y } : undefined, Math.max(4, (outline?.r ?? 0) + 3));
    place(moveHandle, handles?.move, 6);
    place(aimHandle, handles?.aim, 5);
    const from = handles?.origin;
    const to = handles?.aim;
    for (const line of [aimLineDark, aimLine]) {
      setIfChanged(line, 'display', from && to ? 'inline' : 'none');
      if (!from || !to) continue;
      setIfChanged(line, 'x1', from.x.toFixed(1));
      setIfChanged(line, 'y1', from.y.toFixed(1));
      setIfChanged(line, 'x2', to.x.toFixed(1));
      setIfChanged(line, 'y2', to.y.toFixed(1));
    }
  };
  app.onChange(draw);
  // Drags and wheel edits change the scene between history events: follow every frame.
  const follow = () => {
    draw();
    requestAnimationFrame(follow);
  };
  requestAnimationFrame(follow);
}

/** Eight short rays around a sun marker's disc (CSS pixels from its centre). */
const SUN_RAYS = Array.from({ length: 8 }, (_, k) => {
  const [c, s] = [Math.cos((k * Math.PI) / 4), Math.sin((k * Math.PI) / 4)];
  return `M${(5.5 * c).toFixed(2)} ${(5.5 * s).toFixed(2)}L${(8.5 * c).toFixed(2)} ${(8.5 * s).toFixed(2)}`;
}).join('');

/**
 * The directional lights' markers (a small sun each, under the outline and
 * the handles, inserted before `below`): pressed through the canvas's input,
 * like the handles. Each is also a button for the keyboard: focusable, named
 * by `label` (light index: "light 3: directional"), and Enter or Space on it
 * selects its light (`choose`), as a click does. Returns the function that
 * places them.
 */
/**
 * Sets an attribute only when its value changes. The overlay is drawn every
 * frame, and a write, even of the same value, repaints the page: every
 * repaint is a compositor frame, which headless on SwiftShader reads the page
 * back (~17 ms at 1400x1000) after all GPU work queued before it, path
 * tracing included (bench/results/frame-pacing-2026-12-06.md).
 */
function setIfChanged(e: Element, name: string, value: string): void {
  if (e.getAttribute(name) !== value) e.setAttribute(name, value);
}

function sunMarkerLayer(
  svg: SVGSVGElement,
  below: Element,
  choose: (index: number) => void,
  label: (index: number) => string,
): (suns: { index: number; x: number; y: number }[]) => void {
  const markers: SVGGElement[] = [];
  const newMarker = () => {
    const group = document.createElementNS(SVG_NS, 'g');
    group.dataset.testid = 'sun-marker';
    group.setAttribute('class', 'sun-marker');
    group.setAttribute('role', 'button');
    group.setAttribute('tabindex', '0');
    for (const [tag, className, r] of [['circle', 'sun-focus', '11'], ['path', 'sun-rays-dark'], ['path', 'sun-rays'], ['circle', 'sun-disc', '3.5']]) {
      const part = document.createElementNS(SVG_NS, tag);
      part.setAttribute('class', className);
      if (tag === 'path') part.setAttribute('d', SUN_RAYS);
      else part.setAttribute('r', r);
      group.append(part);
    }
    group.addEventListener('keydown', (event) => {
      if (event.key !== 'Enter' && event.key !== ' ') return;
      event.preventDefault(); // Space would scroll the page
      choose(Number(group.dataset.light));
    });
    svg.insertBefore(group, below);
    return group;
  };
  return (suns) => {
    while (markers.length < suns.length) markers.push(newMarker());
    while (markers.length > suns.length) markers.pop()!.remove();
    suns.forEach((sun, i) => {
      // Called every frame: write only what changed.
      setIfChanged(markers[i], 'transform', `translate(${sun.x.toFixed(1)} ${sun.y.toFixed(1)})`);
      setIfChanged(markers[i], 'data-light', String(sun.index));
      setIfChanged(markers[i], 'aria-label', label(sun.index));
    });
  };
}

void start();
