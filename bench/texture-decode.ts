/**
 * Texture image decoding in the page's Worker (src/render/images/): the time
 * to decode a 2048 x 2048 PNG (8-bit RGBA and 16-bit RGB), JPEG and WebP
 * (made here: a photo-like texture of gradients and noise, JPEG/WebP by the
 * browser's own encoder at quality 0.9), and how exact each read-back of the
 * browser's decoded bitmap is on the lossless WebP fixture with every alpha.
 *
 *   npm run build:web && npx tsx bench/texture-decode.ts [--runs 3]
 */
import { readFileSync } from 'node:fs';
import { encode as encodePng } from 'fast-png';
import { PNG } from 'pngjs';
import { openRenderSession } from '../src/node/session';

const SIZE = 2048;
const runs = Number(process.argv[process.argv.indexOf('--runs') + 1]) || 3;
const b64 = (a: Uint8Array) => Buffer.from(a.buffer, a.byteOffset, a.byteLength).toString('base64');

function texture(): Uint8Array {
  const rgba = new Uint8Array(SIZE * SIZE * 4);
  let seed = 1;
  const noise = () => ((seed = (seed * 1664525 + 1013904223) >>> 0) >>> 24) / 16;
  for (let y = 0; y < SIZE; y++) {
    for (let x = 0; x < SIZE; x++) {
      const i = (y * SIZE + x) * 4;
      rgba[i] = (x / 8 + noise()) & 255;
      rgba[i + 1] = (y / 8 + 40 * Math.sin(x / 50) + noise()) & 255;
      rgba[i + 2] = ((x + y) / 16 + noise()) & 255;
      rgba[i + 3] = 255;
    }
  }
  return rgba;
}

async function main(): Promise<void> {
  const session = await openRenderSession();
  const page = session.page;
  try {
    const rgba = texture();
    const rgb16 = new Uint16Array(SIZE * SIZE * 3);
    for (let p = 0; p < SIZE * SIZE; p++) for (let c = 0; c < 3; c++) rgb16[p * 3 + c] = rgba[p * 4 + c] * 257;
    const files: Record<string, string> = {
      'PNG 8-bit RGBA': b64(encodePng({ width: SIZE, height: SIZE, data: rgba, channels: 4, depth: 8 })),
      'PNG 16-bit RGB': b64(encodePng({ width: SIZE, height: SIZE, data: rgb16, channels: 3, depth: 16 })),
      JPEG: await page.evaluate(([t]) => window.pathtraceImages.encode(t, 2048, 2048, 'image/jpeg', 0.9), [b64(rgba)] as const),
      WebP: await page.evaluate(([t]) => window.pathtraceImages.encode(t, 2048, 2048, 'image/webp', 0.9), [b64(rgba)] as const),
    };
    for (const [name, file] of Object.entries(files)) {
      const times: string[] = [];
      for (let r = 0; r < runs; r++) {
        const result = await page.evaluate(([f]) => window.pathtraceImages.decode(f), [file] as const);
        if ('error' in result) throw new Error(`${name}: ${result.error}`);
        times.push(`${result.timings.decodeMs.toFixed(0)}/${result.timings.totalMs.toFixed(0)}`);
      }
      console.log(`${name} ${SIZE}x${SIZE} (${(Buffer.from(file, 'base64').length / 2 ** 20).toFixed(1)} MB): decode in the Worker / request to result, ms: ${times.join(', ')}`);
    }
    const expected = PNG.sync.read(readFileSync(new URL('../test/fixtures/textures/alpha.png', import.meta.url))).data;
    const webp = b64(new Uint8Array(readFileSync(new URL('../test/fixtures/textures/alpha-lossless.webp', import.meta.url))));
    for (const readback of ['webgl', '2d'] as const) {
      const result = await page.evaluate(([f, r]) => window.pathtraceImages.decode(f, r), [webp, readback] as const);
      if ('error' in result) throw new Error(result.error);
      const got = Buffer.from(result.data, 'base64');
      let wrong = 0;
      let wrongOpaque = 0;
      let maxError = 0;
      for (let i = 0; i < expected.length; i += 4) {
        let d = 0;
        for (let c = 0; c < 4; c++) d = Math.max(d, Math.abs(got[i + c] - expected[i + c]));
        if (d > 0) wrong++;
        if (d > 0 && expected[i + 3] === 255) wrongOpaque++;
        if (expected[i + 3] > 0) maxError = Math.max(maxError, d);
      }
      console.log(`read-back ${readback}: ${wrong} of 4096 texels differ (${wrongOpaque} opaque), largest difference where alpha > 0: ${maxError}`);
    }
  } finally {
    await session.close();
  }
}

await main();
