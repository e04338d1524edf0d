/** Acquiring a WebGL2 context that can render to float targets. */

export class WebGLUnavailableError extends Error {
  constructor(message: string) {
    super(message);
    this.name = 'WebGLUnavailableError';
  }
}

export type AnyCanvas = HTMLCanvasElement | OffscreenCanvas;

export function createContext(canvas: AnyCanvas, preserveDrawingBuffer: boolean): WebGL2RenderingContext {
  const gl = canvas.getContext('webgl2', {
    antialias: false,
    depth: false,
    stencil: false,
    alpha: false,
    premultipliedAlpha: false,
    preserveDrawingBuffer,
    powerPreference: 'high-performance',
  }) as WebGL2RenderingContext | null;
  if (!gl) throw new WebGLUnavailableError('WebGL2 is not available in this browser.');
  requireFloatTargets(gl);
  return gl;
}

export function requireFloatTargets(gl: WebGL2RenderingContext): void {
  if (!gl.getExtension('EXT_color_buffer_float')) {
    throw new WebGLUnavailableError('This browser cannot render to float targets (EXT_color_buffer_float is missing).');
  }
}

/** "vendor / renderer" as the browser reports them, unmasked when allowed. */
export function rendererInfo(gl: WebGL2RenderingContext): string {
  const debug = gl.getExtension('WEBGL_debug_renderer_info');
  const vendor = debug ? gl.getParameter(debug.UNMASKED_VENDOR_WEBGL) : gl.getParameter(gl.VENDOR);
  const renderer = debug ? gl.getParameter(debug.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);
  return `${vendor} / ${renderer}`;
}
