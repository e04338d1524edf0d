/**
 * Untrusted scenes (files and share links): they are parsed as JSON and
 * validated, size-limited, never inserted into the page as HTML, and the page
 * runs under a Content-Security-Policy that forbids inline script and eval.
 */
import { existsSync, readdirSync, readFileSync, statSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { compressToEncodedURIComponent, decompressFromEncodedURIComponent } from 'lz-string';
import { SHARE_PREFIX, sceneFromHash, shareHash } from '../../src/app/files';
import { lzDecompressedLength } from '../../src/app/lzLength';
import { MAX_SCENE_BYTES } from '../../src/scene/limits';
import { SceneError, parseScene, parseSceneText, safeParseSceneText } from '../../src/scene/schema';

const ROOT = fileURLToPath(new URL('../../', import.meta.url));
const DIST_WEB = join(ROOT, 'dist/web');

function filesUnder(dir: string, extensions: string[]): string[] {
  if (!existsSync(dir)) return [];
  return readdirSync(dir).flatMap((name) => {
    const path = join(dir, name);
    if (statSync(path).isDirectory()) return filesUnder(path, extensions);
    return extensions.some((ext) => name.endsWith(ext)) ? [path] : [];
  });
}

/** The CSP of an HTML document's meta tag, as directive -> sources. */
function cspOf(html: string): Map<string, string[]> {
  const meta = /<meta\s+http-equiv=["']Content-Security-Policy["']\s+content=(?:"([^"]*)"|'([^']*)')/i.exec(html);
  expect(meta, 'a Content-Security-Policy meta tag').not.toBeNull();
  return new Map(
    (meta![1] ?? meta![2])
      .split(';')
      .map((d) => d.trim().split(/\s+/))
      .filter((d) => d[0])
      .map(([name, ...sources]) => [name.toLowerCase(), sources]),
  );
}

function checkPage(file: string): void {
  const html = readFileSync(file, 'utf8');
  const csp = cspOf(html);
  const scripts = csp.get('script-src') ?? csp.get('default-src');
  expect(scripts, `${file}: script-src or default-src`).toBeDefined();
  for (const forbidden of ["'unsafe-inline'", "'unsafe-eval'", "'unsafe-hashes'", "'wasm-unsafe-eval'", '*', 'data:', 'blob:', 'http:', 'https:']) {
    expect(scripts, `${file}: script-src allows ${forbidden}`).not.toContain(forbidden);
  }
  expect(csp.get('default-src'), `${file}: default-src`).toEqual(["'self'"]);
  const objects = csp.get('object-src') ?? csp.get('default-src');
  expect(objects).not.toContain('*');
  // No inline script (it would be blocked anyway) and no inline event handlers.
  for (const tag of html.match(/<script\b[^>]*>/gi) ?? []) expect(tag, `${file}: inline script`).toMatch(/\ssrc=/);
  expect(html, `${file}: inline event handler`).not.toMatch(/<[^>]+\son[a-z]+\s*=/i);
}

/** Source text without comments, so a comment that names a sink does not count. */
function code(file: string): string {
  return readFileSync(file, 'utf8')
    .replace(/\/\*[\s\S]*?\*\//g, '')
    .replace(/(^|[^:'"`\\])\/\/.*$/gm, '$1');
}

const HTML_SINKS: [string, RegExp][] = [
  ['innerHTML', /\binnerHTML\b/],
  ['outerHTML', /\bouterHTML\b/],
  ['insertAdjacentHTML', /\binsertAdjacentHTML\b/],
  ['document.write', /\bdocument\s*\.\s*write(ln)?\b/],
  ['eval', /(^|[^.\w$])eval\s*\(/],
  ['new Function', /\bnew\s+Function\b|(^|[^.\w$])Function\s*\(/],
  ['string timer', /\bset(Timeout|Interval)\s*\(\s*['"`]/],
  ['createContextualFragment', /\bcreateContextualFragment\b/],
  ['srcdoc', /\bsrcdoc\b/],
  ['DOMParser', /\bDOMParser\b/],
  ['javascript: URL', /javascript:/i],
];

describe('the page never turns data into HTML or code', () => {
  // src/app is the page; the renderer, scene and headless code run in it too.
  const files = ['src/app', 'src/render', 'src/scene', 'src/headless'].flatMap((dir) => filesUnder(join(ROOT, dir), ['.ts', '.tsx', '.js']));

  it('finds the sources', () => {
    expect(files.some((f) => f.includes('/src/render/'))).toBe(true);
    expect(files.some((f) => f.includes('/src/scene/'))).toBe(true);
  });

  it.each(HTML_SINKS)('no %s in browser code', (_, pattern) => {
    const offenders = files.filter((file) => pattern.test(code(file)));
    expect(offenders.map((f) => f.slice(ROOT.length))).toEqual([]);
  });
});

describe('Content-Security-Policy', () => {
  it.each(['index.html', 'headless.html'])('source %s forbids inline script and eval', (name) => {
    checkPage(join(ROOT, name));
  });

  const built = filesUnder(DIST_WEB, ['.html']);
  it.skipIf(built.length === 0)('every built page in dist/web carries it (needs `npm run build`)', () => {
    expect(built.map((f) => f.slice(DIST_WEB.length + 1)).sort()).toEqual(expect.arrayContaining(['headless.html', 'index.html']));
    for (const file of built) checkPage(file);
  });

  const bundles = filesUnder(join(DIST_WEB, 'assets'), ['.js']);
  it.skipIf(bundles.length === 0)('no built bundle needs eval (the CSP would break it)', () => {
    for (const file of bundles) {
      const text = readFileSync(file, 'utf8');
      expect(text, file).not.toMatch(/(^|[^.\w$])eval\s*\(|\bnew Function\s*\(/);
    }
  });
});

describe('scene text from files and links', () => {
  const valid = '{"camera":{"position":[0,1,5],"target":[0,0,0]}}';
  const tooLarge = { path: '', message: `must be at most ${MAX_SCENE_BYTES} bytes of UTF-8 text` };

  it('accepts a valid scene padded to exactly the limit, rejects one byte more', () => {
    const padded = valid + ' '.repeat(MAX_SCENE_BYTES - valid.length);
    expect(safeParseSceneText(padded).ok).toBe(true);
    const result = safeParseSceneText(padded + ' ');
    expect(result.ok ? [] : result.issues).toEqual([tooLarge]);
    expect(() => parseSceneText(padded + ' ')).toThrow(SceneError);
  });

  it('counts UTF-8 bytes, not characters', () => {
    // 400,000 euro signs are 400,000 characters but 1,200,000 bytes.
    const text = `{"camera":{"position":[0,1,5],"target":[0,0,0]},"x":"${'€'.repeat(400_000)}"}`;
    expect(text.length).toBeLessThan(MAX_SCENE_BYTES);
    const result = safeParseSceneText(text);
    expect(result.ok ? [] : result.issues).toEqual([tooLarge]);
  });

  it('rejects a huge text at once, without parsing it', () => {
    const huge = `[${'1,'.repeat(25_000_000)}1]`; // 50 MB of valid JSON
    const start = performance.now();
    const result = safeParseSceneText(huge);
    const elapsed = performance.now() - start;
    expect(result.ok ? [] : result.issues).toEqual([tooLarge]);
    expect(elapsed, 'milliseconds').toBeLessThan(200);
  });

  it('the slowest 1 MB documents (as many unknown keys as fit) still parse in bounded time', () => {
    // About 10 microseconds per unknown key (issue collection and "did you
    // mean" suggestions): ~1 s for the ~110,000 keys that fit in 1 MB. Bounded,
    // but worth trimming (stop collecting after MAX_REPORTED_ISSUES).
    const head = '{"camera":{"position":[0,1,5],"target":[0,0,0]}';
    const keys: string[] = [];
    for (let i = 0, bytes = head.length + 1; ; i++) {
      const key = `,"${i.toString(36)}":0`;
      if (bytes + key.length > MAX_SCENE_BYTES) break;
      keys.push(key);
      bytes += key.length;
    }
    const text = `${head}${keys.join('')}}`;
    expect(text.length).toBeLessThanOrEqual(MAX_SCENE_BYTES);
    const start = performance.now();
    const result = safeParseSceneText(text);
    expect(result.ok ? 0 : result.issues.length).toBe(101); // 100 shown + "N more problems not shown"
    expect(performance.now() - start, 'milliseconds').toBeLessThan(5000);
  });

  it('is JSON only: no comments, no functions, no trailing garbage', () => {
    for (const text of [
      `${valid} // comment`,
      `{"camera":{"position":[0,1,5],"target":[0,0,0]}, "f": function(){}}`,
      `(${valid})`,
      `${valid};alert(1)`,
    ]) {
      const result = safeParseSceneText(text);
      expect(result.ok, text).toBe(false);
      if (!result.ok) expect(result.issues[0].message).toMatch(/^invalid JSON: /);
    }
  });

  it('a __proto__ or constructor key is an unknown key and pollutes nothing', () => {
    const text = '{"camera":{"position":[0,1,5],"target":[0,0,0],"__proto__":{"polluted":1}},"__proto__":{"polluted":1},"constructor":{"prototype":{"polluted":1}}}';
    const result = safeParseSceneText(text);
    expect(result.ok ? [] : result.issues.map((i) => `${i.path}: ${i.message}`)).toEqual([
      'camera.__proto__: unknown key',
      '__proto__: unknown key',
      'constructor: unknown key',
    ]);
    expect(({} as Record<string, unknown>).polluted).toBeUndefined();
  });

  it('a markup string in a scene is reported as data: error messages quote no input', () => {
    const text = '{"camera":{"position":[0,1,5],"target":[0,0,0]},"<img src=x onerror=alert(1)>":1,"spheres":[{"center":[0,0,0],"radius":"<script>"}]}';
    const result = safeParseSceneText(text);
    expect(result.ok).toBe(false);
    if (result.ok) return;
    // Paths quote unusual keys (to be shown with textContent); messages never echo values.
    expect(result.issues.map((i) => i.message).sort()).toEqual(['must be a number', 'unknown key']);
    for (const issue of result.issues) expect(issue.message).not.toContain('<');
  });
});

/**
 * A hand-made lz-string stream (decompressFromEncodedURIComponent's format)
 * of one literal "a" followed by `codes` codes that each name the dictionary
 * entry being defined (LZW's KwKwK case): entry k is k+1 letters long, so the
 * output grows as codes^2 / 2 while the link grows linearly. 20,000 codes are
 * a 41 KB link that expands to 200 million characters.
 */
function lzBomb(codes: number): string {
  const KEY = 'ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+-$';
  const bits: number[] = [];
  const put = (value: number, n: number) => {
    for (let i = 0; i < n; i++) bits.push((value >> i) & 1);
  };
  put(0, 2); // an 8-bit literal follows
  put(97, 8); // "a"
  let dictSize = 4;
  let numBits = 3;
  let enlargeIn = 4;
  for (let k = 0; k < codes; k++) {
    put(dictSize, numBits);
    dictSize++;
    if (--enlargeIn === 0) {
      enlargeIn = 2 ** numBits;
      numBits++;
    }
  }
  put(2, numBits); // end of stream
  while (bits.length % 6) bits.push(0);
  let out = '';
  for (let i = 0; i < bits.length; i += 6) out += KEY[bits.slice(i, i + 6).reduce((v, b) => v * 2 + b, 0)];
  return out;
}

describe('share links', () => {
  it('lzDecompressedLength agrees with lz-string on real, random and damaged links', () => {
    let state = 7;
    const random = () => (state = (Math.imul(state, 1103515245) + 12345) >>> 0) / 2 ** 32;
    const texts = [JSON.stringify(parseScene({ camera: { position: [0, 1, 5], target: [0, 0, 0] } }))];
    for (let i = 0; i < 300; i++) {
      const length = Math.floor(random() * 400);
      texts.push(Array.from({ length }, () => String.fromCharCode(32 + Math.floor(random() * (random() < 0.1 ? 2000 : 95)))).join(''));
    }
    for (const text of texts) {
      const payload = compressToEncodedURIComponent(text);
      expect(lzDecompressedLength(payload, Infinity)).toBe(text.length);
      const damaged = payload.slice(0, Math.floor(random() * payload.length));
      const actual = decompressFromEncodedURIComponent(damaged);
      // A truncated stream decompresses to "" or null: any answer <= 0 says "nothing".
      if (actual) expect(lzDecompressedLength(damaged, Infinity), damaged).toBe(actual.length);
      else expect(lzDecompressedLength(damaged, Infinity), damaged).toBeLessThanOrEqual(0);
    }
  });

  it('round-trip a scene; a damaged or foreign link is an error, not an exception', () => {
    const scene = parseScene({ camera: { position: [0, 1, 5], target: [0, 0, 0] }, spheres: [{ center: [0, 0, 0], radius: 1 }] });
    const result = sceneFromHash(shareHash(scene));
    expect(result?.ok && result.scene).toStrictEqual(scene);
    expect(sceneFromHash('#other')).toBeNull();
    for (const hash of [SHARE_PREFIX, `${SHARE_PREFIX}%%%`, `${SHARE_PREFIX}${'A'.repeat(1000)}`, `${SHARE_PREFIX}${'x'.repeat(MAX_SCENE_BYTES + 1)}`]) {
      const bad = sceneFromHash(hash);
      expect(bad?.ok, hash.slice(0, 40)).toBe(false);
    }
  });

  it('the bomb is what it claims (sanity of the generator)', () => {
    expect(decompressFromEncodedURIComponent(lzBomb(100))).toBe('a'.repeat((101 * 102) / 2));
  });

  // LZW output grows quadratically in the input, so a 41 KB link could expand
  // to 200 M characters; sceneFromHash measures the output length from the
  // bit stream (src/app/lzLength.ts) before decompressing anything.
  it('a decompression bomb is rejected fast, before it expands', () => {
    const hash = SHARE_PREFIX + lzBomb(20_000);
    expect(hash.length).toBeLessThan(50_000);
    const start = performance.now();
    const result = sceneFromHash(hash);
    const elapsed = performance.now() - start;
    expect(result?.ok).toBe(false);
    expect(elapsed, 'milliseconds to reject a 41 KB link').toBeLessThan(50);
  });
});
