/** Float render targets: the ping-pong pair that holds the running sums. */
import { createDataTexture } from './dataTexture';

export class FloatTarget {
  readonly texture: WebGLTexture;
  readonly framebuffer: WebGLFramebuffer;

  constructor(
    private readonly gl: WebGL2RenderingContext,
    readonly width: number,
    readonly height: number,
  ) {
    // RGBA32F is not filterable in WebGL2: every read is a texelFetch.
    this.texture = createDataTexture(gl, width, height);
    this.framebuffer = gl.createFramebuffer()!;
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.framebuffer);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, this.texture, 0);
    const status = gl.checkFramebufferStatus(gl.FRAMEBUFFER);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    if (status !== gl.FRAMEBUFFER_COMPLETE && !gl.isContextLost()) {
      throw new Error(`RGBA32F render target is not supported (framebuffer status 0x${status.toString(16)})`);
    }
  }

  clear(): void {
    const gl = this.gl;
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.framebuffer);
    gl.clearBufferfv(gl.COLOR, 0, [0, 0, 0, 0]);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  }

  /** Reads the whole target; rows bottom to top, as GL stores them. */
  read(): Float32Array {
    const gl = this.gl;
    const data = new Float32Array(this.width * this.height * 4);
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.framebuffer);
    gl.readPixels(0, 0, this.width, this.height, gl.RGBA, gl.FLOAT, data);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    return data;
  }

  dispose(): void {
    this.gl.deleteTexture(this.texture);
    this.gl.deleteFramebuffer(this.framebuffer);
  }
}

/** Two targets: each draw reads one and writes the other (no float blending needed). */
export class PingPong {
  private targets: [FloatTarget, FloatTarget];

  constructor(
    private readonly gl: WebGL2RenderingContext,
    width: number,
    height: number,
  ) {
    this.targets = [new FloatTarget(gl, width, height), new FloatTarget(gl, width, height)];
    this.clear();
  }

  get read(): FloatTarget { return this.targets[0]; }
  get write(): FloatTarget { return this.targets[1]; }

  swap(): void {
    this.targets = [this.targets[1], this.targets[0]];
  }

  /** Makes `write` a copy of `read` (a draw then changes only the pixels it covers). */
  copyReadToWrite(): void {
    const gl = this.gl;
    const { width, height } = this.read;
    gl.bindFramebuffer(gl.READ_FRAMEBUFFER, this.read.framebuffer);
    gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, this.write.framebuffer);
    gl.blitFramebuffer(0, 0, width, height, 0, 0, width, height, gl.COLOR_BUFFER_BIT, gl.NEAREST);
    gl.bindFramebuffer(gl.READ_FRAMEBUFFER, null);
    gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, null);
  }

  clear(): void {
    this.targets.forEach((t) => t.clear());
  }

  dispose(): void {
    this.targets.forEach((t) => t.dispose());
  }
}
