/**
 * Compile + link time of whole fragment shaders (e.g. dumps of
 * `DUMP_VARIANT=... npx tsx bench/shader-ab.ts`), alternating in one headless
 * Chromium on SwiftShader. A unique comment per compile defeats the program
 * caches. Prints the median per shader.
 *   npx tsx scripts/compile-ab.ts A.frag B.frag [--rounds 5]
 */
import { readFileSync } from 'node:fs';
import { launchChromium } from '../src/node/session';

const VERTEX = `#version 300 es
void main() { gl_Position = vec4(vec2((gl_VertexID << 1) & 2, gl_VertexID & 2) * 2.0 - 1.0, 0.0, 1.0); }`;

async function main(argv: string[]): Promise<void> {
  const files = argv.filter((a, i) => !a.startsWith('--') && argv[i - 1] !== '--rounds');
  const roundsAt = argv.indexOf('--rounds');
  const rounds = roundsAt >= 0 ? Number(argv[roundsAt + 1]) : 5;
  const sources = files.map((f) => readFileSync(f, 'utf8'));
  const browser = await launchChromium();
  try {
    const page = await browser.newPage();
    const times: number[][] = files.map(() => []);
    for (let r = 0; r < rounds; r++) {
      for (let i = 0; i < files.length; i++) {
        const text = sources[i].replace(/^(#version 300 es\n)/, `$1// compile ${Math.random()}\n`);
        const ms = await page.evaluate(
          ([vertex, fragment]) => {
            const gl = new OffscreenCanvas(1, 1).getContext('webgl2')!;
            const start = performance.now();
            const program = gl.createProgram()!;
            for (const [type, source] of [[gl.VERTEX_SHADER, vertex], [gl.FRAGMENT_SHADER, fragment]] as const) {
              const shader = gl.createShader(type)!;
              gl.shaderSource(shader, source);
              gl.compileShader(shader);
              if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(shader) ?? 'compile failed');
              gl.attachShader(program, shader);
            }
            gl.linkProgram(program);
            if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(program) ?? 'link failed');
            // SwiftShader compiles the pipeline at the first draw: make one
            // (every uniform block backed by a zero buffer, so the draw is valid).
            gl.useProgram(program);
            const blocks = gl.getProgramParameter(program, gl.ACTIVE_UNIFORM_BLOCKS) as number;
            for (let b = 0; b < blocks; b++) {
              gl.uniformBlockBinding(program, b, b);
              const buffer = gl.createBuffer();
              gl.bindBuffer(gl.UNIFORM_BUFFER, buffer);
              gl.bufferData(gl.UNIFORM_BUFFER, 65536, gl.STATIC_DRAW);
              gl.bindBufferBase(gl.UNIFORM_BUFFER, b, buffer);
            }
            // Samplers of different types may not share a unit: give each its own (nothing bound reads as zero).
            const uniforms = gl.getProgramParameter(program, gl.ACTIVE_UNIFORMS) as number;
            let unit = 0;
            for (let u = 0; u < uniforms; u++) {
              const info = gl.getActiveUniform(program, u)!;
              if (/SAMPLER/.test(Object.keys(Object.getPrototypeOf(gl)).find((k) => (gl as unknown as Record<string, number>)[k] === info.type) ?? '')) {
                gl.uniform1i(gl.getUniformLocation(program, info.name), unit++);
              }
            }
            gl.bindVertexArray(gl.createVertexArray());
            gl.drawArrays(gl.TRIANGLES, 0, 3);
            gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
            if (gl.getError() !== gl.NO_ERROR) throw new Error('the draw failed: the pipeline was not compiled');
            return performance.now() - start;
          },
          [VERTEX, text] as const,
        );
        times[i].push(ms / 1000);
      }
      console.log(`round ${r + 1}: ${files.map((f, i) => `${f} ${times[i][r].toFixed(2)} s`).join(', ')}`);
    }
    const median = (xs: number[]) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
    console.log(files.map((f, i) => `${f}: median ${median(times[i]).toFixed(2)} s`).join('\n'));
  } finally {
    await browser.close();
  }
}

main(process.argv.slice(2)).catch((error) => {
  console.error(error);
  process.exit(1);
});
