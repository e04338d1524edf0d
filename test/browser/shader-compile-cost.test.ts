/**
 * The trace programs stay cheap to compile on SwiftShader. Its compile time
 * doubled with every if/else in sequence inside a loop (SpirvShader's
 * ExistsPath: test/support/spirvCfg.ts), and one texel fetch or one more
 * ternary of computed values in the wrong place cost tens of seconds
 * (bench/results/compile-time-2026-12-06.md). So every fixture scene's
 * programs are checked through the model, on the SPIR-V that ANGLE really
 * emits for them, without compiling them (no clock: the count is exact).
 */
import { readdirSync } from 'node:fs';
import { describe, expect, it, beforeAll, afterAll } from 'vitest';
import { chromium, type Browser, type Page } from 'playwright-core';
import { CHROMIUM_ARGS, chromiumPath } from '../../src/node/session';
import { compileCost, ifElseCounts, parseSpirv } from '../support/spirvCfg';
import { FIXTURES, fixtureFiles, loadFixtureScene, useRenderSession } from '../support/browser';

/**
 * Queue pops of the model per program. The fixture scenes' programs model
 * at 2k-76k (2026-12-06); before the rewrite the mesh, principled and
 * studio-light programs modelled at 1e8-3e8 and compiled in 4-10 s. Four
 * more if/elses in the bounce loop of the textured program would pass it.
 */
const MAX_COST = 1e6;

/** ANGLE's SPIR-V for a fragment shader (WEBGL_debug_shaders; privileged extensions). */
async function angleSpirv(page: Page, source: string): Promise<Uint32Array> {
  const text = await page.evaluate((src) => {
    const gl = document.createElement('canvas').getContext('webgl2');
    const ext = gl?.getExtension('WEBGL_debug_shaders');
    if (!gl || !ext) return 'ERROR no WEBGL_debug_shaders';
    const shader = gl.createShader(gl.FRAGMENT_SHADER)!;
    gl.shaderSource(shader, src);
    gl.compileShader(shader);
    if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) return `ERROR ${gl.getShaderInfoLog(shader)}`;
    return ext.getTranslatedShaderSource(shader);
  }, source);
  if (text.startsWith('ERROR')) throw new Error(text);
  const words = text.slice(text.indexOf('0x07230203')).match(/0x[0-9A-Fa-f]{8}/g) ?? [];
  return Uint32Array.from(words, (w) => parseInt(w, 16));
}

/** A fragment shader whose loop holds `n` statements (each `body(k)`). */
function loopShader(n: number, body: (k: number) => string): string {
  const statements = Array.from({ length: n }, (_, k) => `    a = x + ${k}.0; c = a > v.x; { ${body(k)} } v.y += x;`).join('\n');
  return `#version 300 es
precision highp float;
uniform int uN;
out vec4 o;
float pick(bool c, float a, float b) { return c ? a : b; }
void main() {
  vec4 v = gl_FragCoord; float x = v.x, a = 0.0; bool c = false;
  for (int i = 0; i < uN; i++) {
${statements}
  }
  o = v + x;
}`;
}

describe('compile cost of the trace programs (SwiftShader ExistsPath model)', () => {
  let browser: Browser;
  let page: Page;
  const session = useRenderSession();

  beforeAll(async () => {
    // retainSPIRVDebugInfo keeps the functions' names (OpName) for the failure message.
    browser = await chromium.launch({
      executablePath: chromiumPath(),
      args: [...CHROMIUM_ARGS, '--enable-privileged-webgl-extensions'],
      env: { ...process.env, ANGLE_FEATURE_OVERRIDES_ENABLED: 'retainSPIRVDebugInfo' },
    });
    page = await browser.newPage();
  });
  afterAll(async () => {
    await browser?.close();
  });

  const cost = async (source: string) => compileCost(parseSpirv(await angleSpirv(page, source)));

  it('the model sees what SwiftShader pays for: if/elses in a loop double it, ifs and picks do not', async () => {
    const ifElse = (n: number) => loopShader(n, (k) => `x = c ? a * ${k + 2}.0 : sqrt(a);`);
    const [ten, twelve] = [await cost(ifElse(10)), await cost(ifElse(12))];
    expect(twelve / ten).toBeGreaterThan(3.5); // two more if/elses: 4x
    expect(twelve).toBeGreaterThan(2 ** 12);
    expect(await cost(loopShader(12, (k) => `x = pick(c, a * ${k + 2}.0, sqrt(a));`))).toBeLessThan(100);
    expect(await cost(loopShader(12, (k) => `if (c) { x = sqrt(a) * ${k + 2}.0; }`))).toBeLessThan(2000);
  });

  const scenes = readdirSync(new URL('scenes/', FIXTURES)).filter((f) => f.endsWith('.json')).map((f) => f.replace('.json', ''));
  it(`every fixture scene's programs model under ${MAX_COST} (${scenes.length} scenes)`, async () => {
    const { page: renderPage } = session();
    // The sources the page hands to WebGL while it loads each scene (no draw: nothing is compiled by SwiftShader).
    await renderPage.evaluate(() => {
      const w = window as unknown as { __fragments: Set<string> };
      w.__fragments = new Set();
      const original = WebGL2RenderingContext.prototype.shaderSource;
      WebGL2RenderingContext.prototype.shaderSource = function (shader, source) {
        if (source.includes('void main')) w.__fragments.add(source);
        return original.call(this, shader, source);
      };
    });
    const failures: string[] = [];
    let programs = 0;
    for (const name of scenes) {
      const scene = loadFixtureScene(name);
      await session().load(scene, { width: 32, height: 24, seed: 1 }, fixtureFiles(scene));
      const sources: string[] = await renderPage.evaluate(() => {
        const w = window as unknown as { __fragments: Set<string> };
        const list = [...w.__fragments];
        w.__fragments.clear();
        return list.filter((s) => s.includes('traceRadiance'));
      });
      for (const source of sources) {
        programs++;
        const module = parseSpirv(await angleSpirv(page, source));
        const c = compileCost(module, 10 * MAX_COST);
        if (c >= MAX_COST) {
          const worst = [...ifElseCounts(module)].sort((a, b) => b[1] - a[1]).slice(0, 10).map(([f, n]) => `${f} ${n}`).join(', ');
          failures.push(`${name}: modelled cost ${c}; if/else constructs by function: ${worst}`);
        }
      }
    }
    // Scenes with the same features share a program (19 distinct on 2026-12-06).
    console.log(`${programs} distinct trace programs`);
    expect(programs, 'trace programs seen').toBeGreaterThanOrEqual(15);
    expect(failures, failures.join('\n')).toEqual([]);
  });
});
