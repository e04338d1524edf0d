/**
 * Adaptive sampling's per-cell table on the GPU: an RGBA32UI texture of one
 * texel per cell (x = first sample, y = samples of the draw; trace.frag
 * uCellSamples) and a vertex buffer listing the cells to draw (attribute 0,
 * fullscreen.vert aCell). A 1x1 zero texture until the first upload, so the
 * sampler always has a texture of its type.
 */
import { createDataTexture } from './dataTexture';

/** fullscreen.vert's `layout(location = 0) in float aCell`. */
const CELL_ATTRIBUTE = 0;

export class CellTable {
  texture: WebGLTexture;
  private size = { columns: 1, rows: 1 };
  private readonly list: WebGLBuffer;

  constructor(private readonly gl: WebGL2RenderingContext) {
    this.texture = createDataTexture(gl, 1, 1, new Uint32Array(4), 'rgba32ui');
    gl.bindTexture(gl.TEXTURE_2D, null);
    this.list = gl.createBuffer()!;
  }

  /** `texels`: RGBA per cell, row-major over columns x rows; `cells`: the cell numbers to draw. */
  upload(columns: number, rows: number, texels: Uint32Array, cells: Float32Array): void {
    const gl = this.gl;
    if (columns !== this.size.columns || rows !== this.size.rows) {
      gl.deleteTexture(this.texture);
      this.texture = createDataTexture(gl, columns, rows, texels, 'rgba32ui');
      this.size = { columns, rows };
    } else {
      gl.bindTexture(gl.TEXTURE_2D, this.texture);
      gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, columns, rows, gl.RGBA_INTEGER, gl.UNSIGNED_INT, texels);
    }
    gl.bindTexture(gl.TEXTURE_2D, null);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.list);
    gl.bufferData(gl.ARRAY_BUFFER, cells, gl.DYNAMIC_DRAW);
    gl.bindBuffer(gl.ARRAY_BUFFER, null);
  }

  /** Feeds the listed cells to attribute 0 (in the vertex array bound now) until disableList. */
  enableList(): void {
    const gl = this.gl;
    gl.bindBuffer(gl.ARRAY_BUFFER, this.list);
    gl.enableVertexAttribArray(CELL_ATTRIBUTE);
    gl.vertexAttribPointer(CELL_ATTRIBUTE, 1, gl.FLOAT, false, 0, 0);
    gl.bindBuffer(gl.ARRAY_BUFFER, null);
  }

  disableList(): void {
    this.gl.disableVertexAttribArray(CELL_ATTRIBUTE);
  }

  dispose(): void {
    this.gl.deleteTexture(this.texture);
    this.gl.deleteBuffer(this.list);
  }
}
