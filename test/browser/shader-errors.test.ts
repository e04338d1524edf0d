/**
 * A shader that fails to compile reports its log with each error mapped back
 * to the chunk and line it came from, and the offending source line (what
 * the page shows in its failure message).
 */
import { describe, expect, it } from 'vitest';
import { useRenderSession } from '../support/browser';

describe('shader compile errors', () => {
  const session = useRenderSession();

  it('name the chunk and line of each error and quote the source', async () => {
    const source = ['out vec4 outColor;', 'void main() {', '  outColor = vec4(undefinedThing, 1.0);', '}'].join('\n');
    const log = await session().compileLog('broken.glsl', source);
    expect(log).toMatch(/fragment shader failed to compile/);
    expect(log).toMatch(/ERROR: broken\.glsl:3: .*undefinedThing/);
    expect(log).toContain('outColor = vec4(undefinedThing, 1.0);');
  });

  it('compile the real chunks without a log', async () => {
    expect(await session().compileLog('ok.glsl', 'out vec4 outColor;\nvoid main() { outColor = vec4(PI); }')).toBeNull();
  });
});
