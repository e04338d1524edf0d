/**
 * What the pieces of a BVH traversal step cost on this machine's WebGL2
 * (SwiftShader): a 512x384 draw whose fragments each run a 64-iteration loop
 * of one kind of work, minus the same loop without it, per quad (4 lanes)
 * and iteration. Kinds: a texelFetch of an RGBA32F 2D array texture at a
 * per-lane address, a chain of scalar float operations, a push and pop on a
 * dynamically indexed local int array, a branch whose sides both hold a
 * fetch. --big: fetches over 16 MB instead of 256 KB. Variants alternate in one Chromium (the machine is shared).
 *   npx tsx bench/swiftshader-costs.ts [--rounds 5]
 */
import { readFileSync } from 'node:fs';
import { launchChromium } from '../src/node/session';

const VERTEX = `#version 300 es
void main() { gl_Position = vec4(vec2((gl_VertexID << 1) & 2, gl_VertexID & 2) * 2.0 - 1.0, 0.0, 1.0); }`;

const ITERATIONS = 64;
/** Texels the fetches touch (a power of 2 minus 1): 16K texels = 256 KB, about the bunny's BVH; 1M = 16 MB. */
let WORKING_SET = 16383;

function fragment(body: string, declarations = '', setup = ''): string {
  return `#version 300 es
precision highp float;
precision highp int;
uniform highp sampler2DArray uT;
uniform highp sampler2D uT2;
uniform highp usampler2D uU2;
uniform int uIterations;
#define WORKING_SET ${WORKING_SET}
out vec4 outColor;
vec4 fetch2d(int i) { i &= WORKING_SET; return texelFetch(uT2, ivec2(i & 2047, i >> 11), 0); }
vec4 fetchU(int i) { i &= WORKING_SET; return uintBitsToFloat(texelFetch(uU2, ivec2(i & 2047, i >> 11), 0)); }
vec4 fetch(int i) { i &= WORKING_SET; return texelFetch(uT, ivec3(i & 2047, (i >> 11) & 511, 0), 0); }
${declarations}
void main() {
  int idx = int(gl_FragCoord.x) * 7919 + int(gl_FragCoord.y) * 104729;
  vec4 acc = vec4(0.0);
  float f = gl_FragCoord.x * 1e-3;
  int stack[32];
  int sp = 0;
${setup}
  for (int k = 0; k < uIterations; k++) {
    idx = (idx * 1103515245 + 12345) & 0x7fffffff;
${body}
  }
  outColor = acc + vec4(f) + vec4(float(idx & 1));
}`;
}

// 8 scalar multiply-adds in 2 independent vec4 chains (SwiftShader keeps a vec4 as 4 SIMD registers: 8 SIMD ops).
const ALU8 = '    acc = acc * 1.0001 + 0.25;';

// One step of the BVH traversal (scene/bvh.glsl) at pseudo-random texels, parts removable by #defines.
// The box test is the shipped one, taken from bvh.glsl with the constants it uses.
const BVH_GLSL = readFileSync(new URL('../src/shaders/scene/bvh.glsl', import.meta.url), 'utf8');
function glslPiece(pattern: RegExp): string {
  const piece = BVH_GLSL.match(pattern)?.[0];
  if (!piece) throw new Error(`bench/swiftshader-costs: ${pattern} is no longer in src/shaders/scene/bvh.glsl`);
  return piece;
}
const STEP_DECLARATIONS = [
  glslPiece(/^const float BVH_NO_HIT = .*;$/m),
  glslPiece(/^const float BVH_BOX_EXIT_SCALE = .*;$/m),
  glslPiece(/^float bvhBoxEntry\([^)]*\) \{\n[\s\S]*?\n\}$/m),
].join('\n');
const STEP_SETUP = `
  vec3 origin = vec3(0.3, 0.2, 0.1) + gl_FragCoord.xyx * 1e-4;
  vec3 dir = normalize(vec3(0.5, 0.4, -1.0) + gl_FragCoord.yxy * 1e-4);
  vec3 invDir = 1.0 / dir;
  mat3 shear = mat3(1.0, 0.0, dir.x / dir.z, 0.0, 1.0, dir.y / dir.z, 0.0, 0.0, 1.0 / dir.z);
  float best = 3e38;
  int bestTexel = -1;
  vec2 barycentric = vec2(0.0);
  int node = 0, triangle = 0, triangleEnd = 0;
`;
function stepBody(parts: { tri?: boolean; box?: boolean; stack?: boolean; fetches?: number }): string {
  const { tri = true, box = true, stack = true, fetches = 4 } = parts;
  return `
    bool isTriangle = triangle < triangleEnd;
    int texel = (isTriangle ? triangle : 4 * max(node, 0)) ^ (idx & 0x3ffc);
    vec4 t0 = fetch(texel);
    vec4 t1 = ${fetches >= 2 ? 'fetch(texel + 1)' : 't0.yzwx'};
    vec4 t2 = ${fetches >= 3 ? 'fetch(texel + 2)' : 't1.yzwx'};
    vec4 t3 = ${fetches >= 4 ? 'fetch(texel + 3)' : 't2.yzwx'};
    ${tri ? `vec3 A = (t0.xyz - origin) * shear;
    vec3 B = (t1.xyz - origin) * shear;
    vec3 C = (t2.xyz - origin) * shear;
    vec3 e = vec3(C.x * B.y - C.y * B.x, A.x * C.y - A.y * C.x, B.x * A.y - B.y * A.x);
    float det = e.x + e.y + e.z;
    float t = dot(e, vec3(A.z, B.z, C.z)) / det;
    bool inside = !(any(lessThan(e, vec3(0.0))) && any(greaterThan(e, vec3(0.0))));
    bool found = isTriangle && inside && det != 0.0 && t > 0.0 && t < best;
    best = found ? t : best;
    bestTexel = found ? texel : bestTexel;
    barycentric = found ? e.yz / det : barycentric;` : 'bool found = isTriangle && t0.x < t1.y; best = found ? t2.z : best;'}
    triangle += isTriangle ? 3 : 0;
    ${box ? `float enter0 = bvhBoxEntry(t0.xyz, t1.xyz, origin, invDir, best);
    float enter1 = bvhBoxEntry(t2.xyz, t3.xyz, origin, invDir, best);` : 'float enter0 = t0.x - origin.x, enter1 = t3.y - origin.y;'}
    int ref0 = int(t0.w * 100.0), ref1 = int(t1.w * 100.0), count0 = int(t2.w * 3.0), count1 = int(t3.w * 3.0);
    bool hit0 = !isTriangle && enter0 < 3e38;
    bool hit1 = !isTriangle && enter1 < 3e38;
    bool leaf0 = hit0 && count0 > 0, leaf1 = hit1 && count1 > 0;
    bool inner0 = hit0 && count0 == 0, inner1 = hit1 && count1 == 0;
    int first0 = 4 + 3 * ref0, first1 = 4 + 3 * ref1;
    int end0 = first0 + 3 * count0, end1 = first1 + 3 * count1;
    triangle = leaf0 ? (leaf1 ? min(first0, first1) : first0) : (leaf1 ? first1 : triangle);
    triangleEnd = leaf0 ? (leaf1 ? max(end0, end1) : end0) : (leaf1 ? end1 : triangleEnd);
    bool nearFirst = enter0 <= enter1;
    ${stack ? 'stack[min(sp, 31)] = nearFirst ? ref1 : ref0;' : ''}
    sp += inner0 && inner1 ? 1 : 0;
    int next = inner0 && inner1 ? (nearFirst ? ref0 : ref1) : (inner0 ? ref0 : (inner1 ? ref1 : -1));
    node = isTriangle ? node : next;
    bool pop = node < 0 && sp > 0;
    int top = ${stack ? 'stack[max(sp - 1, 0)]' : 'sp * 7'};
    node = pop ? top : node;
    sp -= pop ? 1 : 0;
    sp &= 15;
    acc.x += best + float(bestTexel) + barycentric.x;`;
}

const variants = (): Record<string, string> => ({
  stepFull: fragment(stepBody({}), STEP_DECLARATIONS, STEP_SETUP),
  stepNoTri: fragment(stepBody({ tri: false }), STEP_DECLARATIONS, STEP_SETUP),
  stepNoBox: fragment(stepBody({ box: false }), STEP_DECLARATIONS, STEP_SETUP),
  stepNoStack: fragment(stepBody({ stack: false }), STEP_DECLARATIONS, STEP_SETUP),
  step3: fragment(stepBody({ fetches: 3 }), STEP_DECLARATIONS, STEP_SETUP),
  step1: fragment(stepBody({ fetches: 1 }), STEP_DECLARATIONS, STEP_SETUP),
  stepBare: fragment(stepBody({ fetches: 1, tri: false, box: false, stack: false }), STEP_DECLARATIONS, STEP_SETUP),
  loop: fragment(''),
  fetch1: fragment('    acc += fetch(idx);'),
  fetch4: fragment('    acc += fetch(idx) + fetch(idx + 1) + fetch(idx + 2) + fetch(idx + 3);'),
  fetch4dep: fragment('    vec4 a = fetch(idx); vec4 b = fetch(idx + int(a.x * 8.0)); vec4 c = fetch(idx + int(b.x * 8.0)); vec4 d = fetch(idx + int(c.x * 8.0)); acc += d;'),
  alu32: fragment([ALU8, ALU8, ALU8, ALU8].join('\n')),
  alu128: fragment(Array.from({ length: 16 }, () => ALU8).join('\n')),
  stack: fragment('    stack[sp & 31] = idx; sp += (idx & 1); acc.x += float(stack[(sp + 31) & 31]);'),
  stackPush: fragment('    stack[sp & 31] = idx; sp += (idx & 1);'),
  branchFetch: fragment('    if ((idx & 16) != 0) { acc += fetch(idx); } else { acc -= fetch(idx + 5); }'),
  selectFetch: fragment('    acc += ((idx & 16) != 0 ? 1.0 : -1.0) * fetch((idx & 16) != 0 ? idx : idx + 5);'),
  branchFetchUniform: fragment('    if ((k & 1) != 0) { acc += fetch(idx); } else { acc -= fetch(idx + 5); }'),
  innerLoop: fragment('    for (int j = 0; j < (idx & 3); j++) acc += fetch(idx + j);'),
  innerLoopNone: fragment('    for (int j = 0; j < (idx & 3) - 4; j++) acc += fetch(idx + j);'),
  fetch4in2d: fragment('    acc += fetch2d(idx) + fetch2d(idx + 1) + fetch2d(idx + 2) + fetch2d(idx + 3);'),
  fetch4uint: fragment('    acc += fetchU(idx) + fetchU(idx + 1) + fetchU(idx + 2) + fetchU(idx + 3);'),
  fetch4offset: fragment('    int i = idx & WORKING_SET & ~3; ivec2 p = ivec2(i & 2047, i >> 11); acc += texelFetchOffset(uT2, p, 0, ivec2(0, 0)) + texelFetchOffset(uT2, p, 0, ivec2(1, 0)) + texelFetchOffset(uT2, p, 0, ivec2(2, 0)) + texelFetchOffset(uT2, p, 0, ivec2(3, 0));'),
  fetch4offsetArray: fragment('    int i = idx & WORKING_SET & ~3; ivec3 p = ivec3(i & 2047, (i >> 11) & 511, i >> 20); acc += texelFetchOffset(uT, p, 0, ivec2(0, 0)) + texelFetchOffset(uT, p, 0, ivec2(1, 0)) + texelFetchOffset(uT, p, 0, ivec2(2, 0)) + texelFetchOffset(uT, p, 0, ivec2(3, 0));'),
  fetch4aligned: fragment('    int i = idx & WORKING_SET & ~3; acc += fetch(i) + fetch(i + 1) + fetch(i + 2) + fetch(i + 3);'),
  stackUniform: fragment('    stack[k & 31] = idx; acc.x += float(stack[(k + 7) & 31]);'),
  divide: fragment('    f = 1.0 / (f + 1.5);'),
  mat3vec: fragment('    vec3 v = fetch(idx).xyz; acc.xyz += mat3(f, 1.0, 2.0, 3.0, f, 5.0, 6.0, 7.0, f) * v;'),
});

async function main(argv: string[]): Promise<void> {
  const roundsAt = argv.indexOf('--rounds');
  const rounds = roundsAt >= 0 ? Number(argv[roundsAt + 1]) : 5;
  const only = argv.indexOf('--only') >= 0 ? argv[argv.indexOf('--only') + 1].split(',') : Object.keys(variants());
  const names = ['loop', ...only.filter((n) => n !== 'loop')];
  if (argv.includes('--big')) WORKING_SET = (1 << 20) - 1;
  const browser = await launchChromium();
  try {
    const page = await browser.newPage();
    await page.evaluate(
      ([vertex, sources]) => {
        const canvas = new OffscreenCanvas(512, 384);
        const gl = canvas.getContext('webgl2')!;
        const texture = gl.createTexture();
        gl.bindTexture(gl.TEXTURE_2D_ARRAY, texture);
        gl.texStorage3D(gl.TEXTURE_2D_ARRAY, 1, gl.RGBA32F, 2048, 512, 1);
        const data = new Float32Array(2048 * 512 * 4).map(() => Math.random());
        gl.texSubImage3D(gl.TEXTURE_2D_ARRAY, 0, 0, 0, 0, 2048, 512, 1, gl.RGBA, gl.FLOAT, data);
        gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
        gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
        // The same texels as 2D textures: float on unit 1 (uT2), their bits as uint on unit 2 (uU2).
        // (A loop, not a local function: tsx would wrap a named one in __name, which the page lacks.)
        const planes = [
          [gl.TEXTURE1, gl.RGBA32F, gl.RGBA, gl.FLOAT, data],
          [gl.TEXTURE2, gl.RGBA32UI, gl.RGBA_INTEGER, gl.UNSIGNED_INT, new Uint32Array(data.buffer)],
        ] as const;
        for (const [unit, internalFormat, format, type, pixels] of planes) {
          gl.activeTexture(unit);
          gl.bindTexture(gl.TEXTURE_2D, gl.createTexture());
          gl.texStorage2D(gl.TEXTURE_2D, 1, internalFormat, 2048, 512);
          gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, 2048, 512, format, type, pixels);
          gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
          gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
        }
        gl.bindVertexArray(gl.createVertexArray());
        const programs: Record<string, WebGLProgram> = {};
        for (const [name, source] of Object.entries(sources)) {
          const program = gl.createProgram()!;
          for (const [type, text] of [[gl.VERTEX_SHADER, vertex], [gl.FRAGMENT_SHADER, source]] as const) {
            const shader = gl.createShader(type)!;
            gl.shaderSource(shader, text);
            gl.compileShader(shader);
            if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) throw new Error(`${name}: ${gl.getShaderInfoLog(shader)}`);
            gl.attachShader(program, shader);
          }
          gl.linkProgram(program);
          if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(`${name}: ${gl.getProgramInfoLog(program)}`);
          programs[name] = program;
        }
        (globalThis as unknown as { __draw: (name: string, iterations: number) => number }).__draw = (name, iterations) => {
          gl.useProgram(programs[name]);
          gl.uniform1i(gl.getUniformLocation(programs[name], 'uT'), 0);
          gl.uniform1i(gl.getUniformLocation(programs[name], 'uT2'), 1);
          gl.uniform1i(gl.getUniformLocation(programs[name], 'uU2'), 2);
          gl.uniform1i(gl.getUniformLocation(programs[name], 'uIterations'), iterations);
          const start = performance.now();
          gl.drawArrays(gl.TRIANGLES, 0, 3);
          gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
          return performance.now() - start;
        };
      },
      [VERTEX, Object.fromEntries(names.map((n) => [n, variants()[n]]))] as const,
    );
    const draw = (name: string, iterations: number) => page.evaluate(([n, i]) => (globalThis as unknown as { __draw: (name: string, iterations: number) => number }).__draw(n, i), [name, iterations] as const);
    for (const n of names) await draw(n, 1); // compile (SwiftShader compiles at the first draw)
    const times = new Map<string, number[]>(names.map((n) => [n, []]));
    for (let r = 0; r < rounds; r++) {
      for (const n of r % 2 ? [...names].reverse() : names) times.get(n)!.push(await draw(n, ITERATIONS));
    }
    const median = (v: number[]) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];
    const quadIterations = ((512 * 384) / 4) * ITERATIONS;
    const base = median(times.get('loop')!);
    for (const n of names) {
      const ms = median(times.get(n)!);
      console.log(`${n.padEnd(20)} ${ms.toFixed(1)} ms; ${((ms * 1e6) / quadIterations).toFixed(1)} ns per quad-iteration, ${(((ms - base) * 1e6) / quadIterations).toFixed(1)} ns more than the empty loop`);
    }
  } finally {
    await browser.close();
  }
}

main(process.argv.slice(2)).catch((error) => {
  console.error(error);
  process.exit(1);
});
