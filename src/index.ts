/** The library: scene model (no GL) and the WebGL2 renderer. */
export * from './scene/index';
export * from './render/index';
