/**
 * The scene model: types, limits, camera math, parsing and validation,
 * color conversion, serialization and the bundled example scenes.
 * Nothing here touches WebGL or the DOM.
 */
export type * from './types';
export * from './limits';
export * from './camera';
export * from './schema';
export * from './color';
export * from './serialize';
export * from './presets';
export { requiredVersion } from './version';
export { loadSceneAssets, assetReferences, missingAssets, NO_ASSETS, type SceneAssets, type AssetReader, type AssetReference } from './assets';
export { AssetError } from './assetError';
