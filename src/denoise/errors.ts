/**
 * The denoiser's error, in a module of its own: the page's worker client
 * needs it without pulling TensorFlow.js (denoiser.ts) onto the main thread.
 */
export class DenoiseError extends Error {
  constructor(message: string) {
    super(message);
    this.name = 'DenoiseError';
  }
}
