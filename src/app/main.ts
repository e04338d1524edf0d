/**
 * The interactive page: wires the renderer, input, panel, files and
 * statistics together. Untrusted text (files, links, error logs) is only
 * ever shown through textContent.
 */
import './style.css';
import { ShaderCompileError } from '../render/gl/program';
import { WebGLUnavailableError } from '../render/gl/context';
import { formatIssue, parseScene, type SafeParseResult, type SceneIssue } from '../scene/schema';
import { defaultScene, PRESET_NAMES, PRESETS } from '../scene/presets';
import { stringifyScene } from '../scene/serialize';
import type { Scene } from '../scene/types';
import { App } from './App';
import { downloadBlob, readSceneFile, rgba8ToPngBlob, sceneFromHash, shareHash } from './files';
import { attachInput, attachKeys } from './input';
import { Panel } from './panel';
import { encodePfm } from '../image/pfm';
import type { RenderStats } from './renderLoop';

const $ = <T extends HTMLElement = HTMLElement>(id: string) => document.getElementById(id) as T;
const SVG_NS = 'http://www.w3.org/2000/svg';

// ---------------------------------------------------------------- messages

const alertBox = $('error');

function showError(title: string, lines: string[] = [], log?: string): void {
  alertBox.replaceChildren();
  const dismiss = document.createElement('button');
  dismiss.className = 'dismiss';
  dismiss.type = 'button';
  dismiss.textContent = '×';
  dismiss.setAttribute('aria-label', 'Dismiss');
  dismiss.addEventListener('click', clearError);
  const heading = document.createElement('strong');
  heading.textContent = title;
  alertBox.append(dismiss, heading);
  if (lines.length) {
    const list = document.createElement('ul');
    for (const line of lines) {
      const item = document.createElement('li');
      item.textContent = line;
      list.append(item);
    }
    alertBox.append(list);
  }
  if (log) {
    const pre = document.createElement('pre');
    pre.textContent = log;
    alertBox.append(pre);
  }
  alertBox.hidden = false;
}

function clearError(): void {
  alertBox.hidden = true;
  alertBox.replaceChildren();
}

function showIssues(source: string, issues: SceneIssue[]): void {
  showError(`${source} is not a valid scene; the current scene is kept.`, issues.map(formatIssue));
}

let noticeTimer = 0;
function notify(text: string): void {
  const notice = $('notice');
  notice.textContent = text;
  notice.hidden = false;
  clearTimeout(noticeTimer);
  noticeTimer = window.setTimeout(() => (notice.hidden = true), 4000);
}

function showFatal(title: string, detail: string, log?: string): void {
  const area = $('viewport-area');
  const box = document.createElement('div');
  box.className = 'fatal';
  const heading = document.createElement('h2');
  heading.textContent = title;
  const text = document.createElement('p');
  text.textContent = detail;
  box.append(heading, text);
  area.replaceChildren(box);
  showError(title, [detail], log);
  document.body.dataset.state = 'failed';
}

// ---------------------------------------------------------------- start

function initialScene(): Scene {
  const fromLink = sceneFromHash(location.hash);
  if (fromLink && !fromLink.ok) showIssues('The scene in this link', fromLink.issues);
  return fromLink?.ok ? fromLink.scene : defaultScene();
}

function maxRenderWidth(): number {
  const value = Number(new URLSearchParams(location.search).get('maxwidth'));
  return Number.isFinite(value) && value >= 8 ? value : Infinity;
}

function start(): void {
  const canvas = $<HTMLCanvasElement>('viewport');
  let app: App;
  try {
    app = new App(canvas, initialScene(), maxRenderWidth(), showStats);
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
  const panel = new Panel(app, $('panel'));
  attachInput(app, canvas);
  attachKeys(app);
  wireToolbar(app);
  wireFiles(app);
  wireContextLoss(app);
  wireOverlay(app);
  if (window.matchMedia('(max-width: 760px)').matches) panel.gui.close();
  new ResizeObserver(() => app.layout()).observe($('viewport-area'));
  app.layout();
  app.loop.start();
  document.body.dataset.state = 'ready';
}

// ---------------------------------------------------------------- statistics

function showStats(stats: RenderStats): void {
  $('spp').textContent = String(stats.spp);
  $('rate').textContent = `${stats.sppPerSecond.toFixed(stats.sppPerSecond < 10 ? 1 : 0)} spp/s`;
  $('elapsed').textContent = `${(stats.elapsedMs / 1000).toFixed(1)} s`;
  $('resolution').textContent = `${stats.width}×${stats.height}`;
  $('state').textContent = stats.state === 'rendering' ? '' : stats.state;
  document.body.dataset.render = stats.state;
}

// ---------------------------------------------------------------- toolbar

function wireToolbar(app: App): void {
  const click = (id: string, action: () => void) => $(id).addEventListener('click', action);
  click('add-sphere', () => app.addSphere());
  click('add-light', () => app.addLight());
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

function wireFiles(app: App): void {
  const accept = (source: string, result: SafeParseResult) => {
    if (!result.ok) {
      showIssues(source, result.issues);
      return;
    }
    clearError();
    app.load(result.scene);
  };
  const openFile = async (file: File) => accept(`"${file.name}"`, await readSceneFile(file));

  const input = $<HTMLInputElement>('file');
  $('open').addEventListener('click', () => input.click());
  input.addEventListener('change', () => {
    const file = input.files?.[0];
    input.value = '';
    if (file) void openFile(file);
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
    event.preventDefault();
    hint.hidden = true;
    const file = event.dataTransfer?.files[0];
    if (file) void openFile(file);
  });

  const examples = $<HTMLSelectElement>('examples');
  for (const name of PRESET_NAMES) {
    const option = document.createElement('option');
    option.value = name;
    option.textContent = name;
    examples.append(option);
  }
  examples.addEventListener('change', () => {
    const name = examples.value;
    examples.value = '';
    if (name in PRESETS) {
      clearError();
      app.load(parseScene(PRESETS[name]));
    }
  });

  $('save-json').addEventListener('click', () => {
    downloadBlob(new Blob([stringifyScene(app.scene) + '\n'], { type: 'application/json' }), 'scene.json');
  });

  $('share').addEventListener('click', () => {
    const hash = shareHash(app.scene);
    history.replaceState(null, '', hash);
    const url = location.href;
    navigator.clipboard?.writeText(url).then(
      () => notify('Link copied: it carries the whole scene.'),
      () => notify('The page address now carries the scene: copy it from the address bar.'),
    );
  });

  window.addEventListener('hashchange', () => {
    const result = sceneFromHash(location.hash);
    if (result) accept('The scene in this link', result);
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
    const bytes = encodePfm(width, height, app.tracer.readLinear());
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
  app.tracer.on('contextrestored', () => {
    notify('The WebGL context was restored; rendering resumes.');
    app.changed();
  });
}

// ---------------------------------------------------------------- selection outline

function wireOverlay(app: App): void {
  const svg = $('overlay') as unknown as SVGSVGElement;
  const dark = document.createElementNS(SVG_NS, 'circle');
  const light = document.createElementNS(SVG_NS, 'circle');
  dark.setAttribute('class', 'outline-dark');
  light.setAttribute('class', 'outline');
  svg.append(dark, light);
  const draw = () => {
    const outline = app.selectionOutline();
    svg.style.display = outline ? '' : 'none';
    if (!outline) return;
    for (const circle of [dark, light]) {
      circle.setAttribute('cx', outline.x.toFixed(1));
      circle.setAttribute('cy', outline.y.toFixed(1));
      circle.setAttribute('r', Math.max(4, outline.r + 3).toFixed(1));
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

start();
