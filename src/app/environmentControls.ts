/**
 * The panel's Environment folder: no environment, a constant sky, a bundled
 * map or a map file of the user's, with the controls of the one in use.
 * Intensity and rotation are uniforms of the trace program: dragging them
 * re-uploads the scene data but never recompiles, and the map itself is
 * uploaded only when it changes.
 */
import type GUI from 'lil-gui';
import type { Controller } from 'lil-gui';
import { hexToLinear, linearToHex } from '../scene/color';
import type { Environment, Vec3 } from '../scene/types';
import type { App } from './App';
import { BUNDLED_MAP_NAMES, bundledMapFile, bundledMapName } from './bundledMaps';
import type { EnvironmentMaps } from './environmentMaps';

const NONE = 'none';
const CONSTANT = 'constant';
const OPEN = 'open';

/** What the note under the picker says about links. */
export const MAP_LINK_NOTE =
  'A share link carries a bundled map by name. A map you open stays in this browser: a link cannot carry it, so whoever opens the link must open the same file too.';

type Constant = Extract<Environment, { color: Vec3 }>;

export function addEnvironmentControls(
  gui: GUI,
  app: App,
  maps: EnvironmentMaps | null,
  track: <T extends Controller>(controller: T) => T,
): GUI {
  const folder = gui.addFolder('Environment');
  let lastConstant: Constant = { color: [1, 1, 1], intensity: 1 };
  const env = () => app.scene.environment;
  const constant = (): Constant | null => {
    const e = env();
    return e && 'color' in e ? e : null;
  };
  const mapEnv = () => {
    const e = env();
    return e && 'map' in e ? e : null;
  };
  const choose = (value: string) => {
    const current = env();
    if (current && 'color' in current) lastConstant = structuredClone(current);
    if (value === NONE) app.edit((s) => (s.environment = null));
    else if (value === CONSTANT) app.edit((s) => (s.environment = structuredClone(lastConstant)));
    else if (value === OPEN) maps?.openFilePicker();
    else {
      const name = bundledMapName(value);
      if (name) void maps?.useBundled(name);
    }
  };

  const options: Record<string, string> = { 'none (black)': NONE, 'constant color': CONSTANT };
  if (maps) {
    for (const name of BUNDLED_MAP_NAMES) options[`map: ${name}`] = bundledMapFile(name);
    options['open .hdr/.exr…'] = OPEN;
  }
  folder.add({
    get sky() { const e = env(); return e === null ? NONE : 'color' in e ? CONSTANT : e.map; },
    set sky(v: string) { choose(v); },
  }, 'sky', options).name('environment');

  const color = track(folder.addColor({
    get color() { return linearToHex(constant()?.color ?? lastConstant.color); },
    set color(v: string) { app.live(() => { const c = constant(); if (c) c.color = hexToLinear(v); }); },
  }, 'color'));
  const intensity = track(folder.add({
    get intensity() { return env()?.intensity ?? 0; },
    set intensity(v: number) { app.live((s) => { if (s.environment) s.environment.intensity = v; }); },
  }, 'intensity', 0, 10, 0.01));
  const rotation = track(folder.add({
    get rotation() { return mapEnv()?.rotation ?? 0; },
    set rotation(v: number) { app.live(() => { const m = mapEnv(); if (m) m.rotation = v; }); },
  }, 'rotation', -180, 180, 1).name('rotation (deg)'));

  const note = document.createElement('p');
  note.className = 'panel-note';
  note.dataset.testid = 'map-note';
  note.textContent = MAP_LINK_NOTE;
  folder.$children.append(note);

  const update = () => {
    const e = env();
    color.show(e !== null && 'color' in e);
    intensity.show(e !== null);
    rotation.show(e !== null && 'map' in e);
    note.hidden = !maps;
  };
  app.onChange(update);
  update();
  return folder;
}
