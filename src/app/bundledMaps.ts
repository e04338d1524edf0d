/**
 * The environment maps the page ships: CC0 maps from Poly Haven as packaged
 * by the npm package @pmndrs/assets (OpenEXR, DWAB-compressed, 512 x 256,
 * base64 in a JS module). Each is its own lazily loaded chunk (150-210 kB),
 * fetched the first time it is chosen, and decoded by the project's own
 * decoder in the map Worker like any user file.
 *
 * A scene names a bundled map as `bundled/NAME.exr`: a plain relative path,
 * so a share link can carry it (the page resolves it from the bundle) and
 * the command-line renderer finds it when the file is put in a `bundled`
 * folder beside the scene.
 */

export const BUNDLED_PREFIX = 'bundled/';

const LOADERS: Record<string, () => Promise<{ default: string }>> = {
  studio: () => import('@pmndrs/assets/hdri/studio.exr.js'),
  city: () => import('@pmndrs/assets/hdri/city.exr.js'),
  sunset: () => import('@pmndrs/assets/hdri/sunset.exr.js'),
  park: () => import('@pmndrs/assets/hdri/park.exr.js'),
};

export const BUNDLED_MAP_NAMES = Object.keys(LOADERS);

/** The scene's `environment.map` for a bundled map. */
export const bundledMapFile = (name: string) => `${BUNDLED_PREFIX}${name}.exr`;

/** The bundled map a scene's `environment.map` names, or null. */
export function bundledMapName(file: string): string | null {
  if (!file.startsWith(BUNDLED_PREFIX) || !file.endsWith('.exr')) return null;
  const name = file.slice(BUNDLED_PREFIX.length, -'.exr'.length);
  return Object.hasOwn(LOADERS, name) ? name : null;
}

/** The file bytes of a bundled map (loads its chunk). */
export async function bundledMapBytes(name: string): Promise<Uint8Array> {
  const module = await LOADERS[name]();
  return dataUrlBytes(module.default);
}

/** The bytes of a base64 `data:` URL (the page's CSP lets it fetch none). */
export function dataUrlBytes(url: string): Uint8Array {
  const base64 = url.slice(url.indexOf(',') + 1);
  const text = atob(base64);
  const bytes = new Uint8Array(text.length);
  for (let i = 0; i < text.length; i++) bytes[i] = text.charCodeAt(i);
  return bytes;
}
