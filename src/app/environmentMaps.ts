/**
 * Choosing the environment map on the page: a bundled map, or a `.hdr` /
 * `.exr` file the user opens or drops. Every change goes through a
 * SceneLoader (read, decode in the Worker, then apply or reject): a map that
 * fails to load is reported naming `environment.map` and changes nothing.
 * Applying is one undoable edit of `environment` only (camera, selection and
 * the rest of the scene stay); the user's file is kept with the autosave.
 */
import type { Environment, Scene } from '../scene/types';
import type { SceneIssue } from '../scene/schema';
import type { App } from './App';
import { bundledMapFile } from './bundledMaps';
import { recordApplyTime } from './mapDecoder';
import { SceneLoader, type CompanionFiles } from './sceneLoader';

/** Map files the page opens (by extension; the decoder checks the signature). */
export const MAP_FILE_PATTERN = /\.(hdr|exr)$/i;

export interface MapKeeper {
  keepFiles(scene: Scene, files: CompanionFiles): Promise<void>;
}

export class EnvironmentMaps {
  private readonly loader: SceneLoader;
  /** A user's file is decoded again even when a map of that name was loaded before (it may have changed). */
  private fresh = false;

  constructor(
    private readonly app: App,
    private readonly keeper: MapKeeper,
    reject: (source: string, issues: SceneIssue[]) => void,
    private readonly applied: () => void = () => {},
  ) {
    const known = () => (this.fresh ? { ...app.assets, maps: new Map() } : app.assets);
    this.loader = new SceneLoader((scene, assets, files) => this.apply(scene, assets, files), reject, known);
  }

  /** Uses bundled map `name` (keeping the current map's intensity and rotation). */
  useBundled(name: string): Promise<boolean> {
    return this.use(`The map "${name}"`, bundledMapFile(name), new Map());
  }

  /** Uses a map file the user opened or dropped; it is named in the scene by its file name. */
  useFile(file: File): Promise<boolean> {
    return this.use(`"${file.name}"`, file.name, new Map([[file.name, file]]));
  }

  /** Asks the user for a map file (the picker's "open .hdr/.exr…"). */
  openFilePicker(): void {
    let input = document.getElementById('map-file') as HTMLInputElement | null;
    if (!input) {
      input = document.createElement('input');
      input.type = 'file';
      input.id = 'map-file';
      input.accept = '.hdr,.exr';
      input.hidden = true;
      input.addEventListener('change', () => {
        const file = input!.files?.[0];
        input!.value = '';
        if (file) void this.useFile(file);
      });
      document.body.append(input);
    }
    input.click();
  }

  private use(source: string, map: string, files: CompanionFiles): Promise<boolean> {
    const current = this.app.scene.environment;
    const environment: Environment = {
      map,
      intensity: current && 'map' in current ? current.intensity : 1,
      rotation: current && 'map' in current ? current.rotation : 0,
    };
    const scene = { ...structuredClone(this.app.scene), environment };
    this.fresh = files.size > 0;
    return this.loader.open(source, () => ({ ok: true, scene }), files);
  }

  private apply(scene: Scene, assets: Parameters<App['addAssets']>[0], files: CompanionFiles): void {
    const environment = structuredClone(scene.environment);
    const start = performance.now();
    this.app.addAssets(assets);
    this.app.edit((s) => (s.environment = environment));
    if (environment && 'map' in environment) recordApplyTime(environment.map, performance.now() - start);
    if (files.size) void this.keeper.keepFiles(scene, files);
    this.applied();
  }
}
