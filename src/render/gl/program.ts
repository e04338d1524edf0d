/** A linked WebGL2 program with cached uniform locations. */
import { buildShader, describeCompileLog, type ShaderChunk } from './shaderSource';

export class ShaderCompileError extends Error {
  constructor(
    readonly stage: 'vertex' | 'fragment' | 'link',
    readonly log: string,
  ) {
    super(`${stage} shader failed to compile:\n${log}`);
    this.name = 'ShaderCompileError';
  }
}

type UniformValue = number | boolean | ArrayLike<number>;

export class Program {
  readonly handle: WebGLProgram;
  private readonly locations = new Map<string, WebGLUniformLocation | null>();

  constructor(
    private readonly gl: WebGL2RenderingContext,
    vertex: ShaderChunk[],
    fragment: ShaderChunk[],
    defines: Record<string, string | number> = {},
  ) {
    const vs = compile(gl, gl.VERTEX_SHADER, vertex, defines);
    const fs = compile(gl, gl.FRAGMENT_SHADER, fragment, defines);
    const program = gl.createProgram()!;
    gl.attachShader(program, vs);
    gl.attachShader(program, fs);
    gl.linkProgram(program);
    gl.deleteShader(vs);
    gl.deleteShader(fs);
    if (!gl.getProgramParameter(program, gl.LINK_STATUS) && !gl.isContextLost()) {
      const log = gl.getProgramInfoLog(program) ?? '';
      gl.deleteProgram(program);
      throw new ShaderCompileError('link', log);
    }
    this.handle = program;
  }

  use(): this {
    this.gl.useProgram(this.handle);
    return this;
  }

  private location(name: string): WebGLUniformLocation | null {
    if (!this.locations.has(name)) this.locations.set(name, this.gl.getUniformLocation(this.handle, name));
    return this.locations.get(name)!;
  }

  /** Sets uniforms by name; the GLSL type decides the call (float, int, uint, uvecN, vecN, mat4). */
  setUniforms(values: Record<string, UniformValue>, types: Record<string, string>): this {
    const gl = this.gl;
    for (const [name, value] of Object.entries(values)) {
      const loc = this.location(name);
      if (loc === null) continue;
      const v = typeof value === 'boolean' ? Number(value) : value;
      switch (types[name]) {
        case 'int': case 'bool': case 'sampler2D': case 'usampler2D': case 'sampler2DArray': gl.uniform1i(loc, v as number); break;
        case 'uint': gl.uniform1ui(loc, v as number); break;
        case 'uvec3': gl.uniform3uiv(loc, v as ArrayLike<number> as Uint32List); break;
        case 'uvec4': gl.uniform4uiv(loc, v as ArrayLike<number> as Uint32List); break;
        case 'float': gl.uniform1f(loc, v as number); break;
        case 'vec2': gl.uniform2fv(loc, v as ArrayLike<number> as Float32List); break;
        case 'vec3': gl.uniform3fv(loc, v as ArrayLike<number> as Float32List); break;
        case 'vec4': gl.uniform4fv(loc, v as ArrayLike<number> as Float32List); break;
        case 'mat4': gl.uniformMatrix4fv(loc, false, v as ArrayLike<number> as Float32List); break;
        default: throw new Error(`uniform ${name}: unknown type ${types[name]}`);
      }
    }
    return this;
  }

  dispose(): void {
    this.gl.deleteProgram(this.handle);
  }
}

function compile(
  gl: WebGL2RenderingContext,
  type: number,
  chunks: ShaderChunk[],
  defines: Record<string, string | number>,
): WebGLShader {
  const source = buildShader(chunks, defines);
  const shader = gl.createShader(type)!;
  gl.shaderSource(shader, source.text);
  gl.compileShader(shader);
  if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS) && !gl.isContextLost()) {
    const log = describeCompileLog(gl.getShaderInfoLog(shader) ?? '', source);
    gl.deleteShader(shader);
    throw new ShaderCompileError(type === gl.VERTEX_SHADER ? 'vertex' : 'fragment', log);
  }
  return shader;
}
