/**
 * Texture images on the page: an image the user opens or drops on a
 * material's texture slot (materialControls.ts). It goes the way of every
 * file (sceneLoader.ts): the scene with the texture is validated by the one
 * parser and its files decoded (images in the image Worker, never on this
 * thread) before anything changes; an image that cannot be used (corrupt,
 * too large, KTX2, over the scenes' image memory, a mesh without texture
 * coordinates) is reported naming its key
 * (`meshes[0].material.baseColor.image: "x.png": ...`) and changes nothing:
 * not the scene, not its samples. Applying it is one undoable edit of that
 * input; the file is kept with the autosave.
 */
import { formatIssue, safeParseScene, type SceneIssue } from '../scene/schema';
import { serializeScene } from '../scene/serialize';
import type { TextureImage } from '../scene/texture/image';
import type { Material, Scene } from '../scene/types';
import type { App } from './App';
import type { MapKeeper } from './environmentMaps';
import { materialControls } from '../materials/registry';
import { withTexture, type TextureSlots } from './materialControls';
import { SceneLoader, type CompanionFiles } from './sceneLoader';
import type { SceneAssets } from '../scene/assets';

/** Image files the slots' picker offers (the decoders check the signature). */
const IMAGE_ACCEPT = '.png,.jpg,.jpeg,.webp,.exr,.hdr,image/png,image/jpeg,image/webp';

/** Finds the material a slot edits in a scene (the live one or a copy); undefined once its object is gone. */
export type MaterialIn = (scene: Scene) => Material | undefined;

interface Request {
  materialIn: MaterialIn;
  key: string;
  file: File;
}

export class TextureImages {
  private readonly loader: SceneLoader;
  private request: Request | null = null;

  constructor(
    private readonly app: App,
    private readonly keeper: MapKeeper,
    showError: (title: string, lines: string[]) => void,
  ) {
    const reject = (source: string, issues: SceneIssue[]) => showError(`${source} could not be used; the scene is unchanged.`, issues.map(formatIssue));
    this.loader = new SceneLoader((scene, assets, files) => this.apply(assets, files), reject, () => this.known());
  }

  /** The slots of the material `materialIn` finds. */
  slotsFor(materialIn: MaterialIn): TextureSlots {
    return {
      useFile: (key, file) => void this.useFile(materialIn, key, file),
      openFilePicker: (key) => this.openFilePicker((file) => void this.useFile(materialIn, key, file)),
      describe: (image) => this.describe(image),
    };
  }

  /** Makes input `key` of the material a texture of `file`; resolves to whether it was applied. */
  useFile(materialIn: MaterialIn, key: string, file: File): Promise<boolean> {
    const candidate = structuredClone(this.app.scene);
    const material = materialIn(candidate);
    if (!material) return Promise.resolve(false);
    withTexture(material, key, file.name);
    this.request = { materialIn, key, file };
    // Parsed again from JSON: the one parser says whether the texture may be there.
    return this.loader.open(`The image "${file.name}"`, () => safeParseScene(serializeScene(candidate)), new Map([[file.name, file]]));
  }

  /** "name.png, 256×256" for a loaded image. */
  describe(image: string): string {
    const decoded = this.app.assets.images?.get(image);
    return decoded ? `${image}, ${decoded.width}×${decoded.height}` : `${image} (not loaded)`;
  }

  /** The files already loaded, but not the one being opened: a user's file is decoded again (it may have changed). */
  private known(): SceneAssets {
    const images = new Map(this.app.assets.images ?? []);
    if (this.request) images.delete(this.request.file.name);
    return { ...this.app.assets, images };
  }

  private apply(assets: SceneAssets, _files: CompanionFiles): void {
    const request = this.request;
    const decoded = request && assets.images?.get(request.file.name);
    if (!request || !decoded) return;
    const name = imageNameFor(this.app.assets.images ?? new Map(), request.file.name, decoded);
    const material = request.materialIn(this.app.scene);
    // The object went away, or became a kind without that input, while the image was decoded.
    if (!material || !materialControls(material).some((c) => c.key === request.key)) return;
    this.app.addAssets({ maps: new Map(), meshes: new Map(), images: new Map([[name, decoded]]) });
    this.app.edit((s) => withTexture(request.materialIn(s)!, request.key, name));
    void this.keeper.keepFiles(this.app.scene, new Map([[name, request.file]]));
  }

  private openFilePicker(use: (file: File) => void): void {
    let input = document.getElementById('texture-file') as HTMLInputElement | null;
    if (!input) {
      input = document.createElement('input');
      input.type = 'file';
      input.id = 'texture-file';
      input.accept = IMAGE_ACCEPT;
      input.hidden = true;
      document.body.append(input);
    }
    const picker = input;
    picker.onchange = () => {
      const file = picker.files?.[0];
      picker.value = '';
      if (file) use(file);
    };
    picker.click();
  }
}

/**
 * The name the scene gives an image file: its own, unless a different image
 * of that name is already loaded (then "name-2.png", ...). The same image
 * again keeps the name, so it is stored and uploaded once.
 */
export function imageNameFor(loaded: ReadonlyMap<string, TextureImage>, name: string, image: TextureImage): string {
  const dot = name.lastIndexOf('.') > 0 ? name.lastIndexOf('.') : name.length;
  for (let n = 1; ; n++) {
    const candidate = n === 1 ? name : `${name.slice(0, dot)}-${n}${name.slice(dot)}`;
    const other = loaded.get(candidate);
    if (!other || sameImage(other, image)) return candidate;
  }
}

function sameImage(a: TextureImage, b: TextureImage): boolean {
  if (a.width !== b.width || a.height !== b.height || a.encoding !== b.encoding || a.data.length !== b.data.length) return false;
  for (let i = 0; i < a.data.length; i++) if (a.data[i] !== b.data[i]) return false;
  return true;
}
