/**
 * A static file server on a free loopback port for the built page
 * (Chromium refuses module scripts from file:// pages), which also hands the
 * page bytes from memory (publish): a fetch of raw bytes is much faster than
 * passing them through Playwright's evaluate as JSON or base64.
 */
import { createReadStream, existsSync, statSync } from 'node:fs';
import { createServer, type Server } from 'node:http';
import type { AddressInfo } from 'node:net';
import { extname, join, normalize, sep } from 'node:path';

const MIME: Record<string, string> = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json',
  '.png': 'image/png',
  '.svg': 'image/svg+xml',
  '.ico': 'image/x-icon',
  '.wasm': 'application/wasm',
};

export interface StaticServer {
  url: string;
  /**
   * Serves `data` once at the returned path (relative to `url`, e.g.
   * `_transfer/1`): the first GET of it gets the bytes and forgets them.
   */
  publish(data: Uint8Array): string;
  close(): Promise<void>;
}

/** The prefix of published paths; not a directory of the page. */
const TRANSFER = '/_transfer/';

export async function serveDirectory(root: string, port = 0, host = '127.0.0.1'): Promise<StaticServer> {
  const published = new Map<string, Uint8Array>();
  let nextId = 1;
  const server: Server = createServer((request, response) => {
    const path = decodeURIComponent(new URL(request.url ?? '/', 'http://localhost').pathname);
    if (path.startsWith(TRANSFER)) {
      const data = published.get(path);
      if (!data) {
        response.writeHead(404).end('not found');
        return;
      }
      published.delete(path);
      response.writeHead(200, { 'Content-Type': 'application/octet-stream', 'Content-Length': data.byteLength, 'Cache-Control': 'no-store' });
      response.end(data);
      return;
    }
    let file = normalize(join(root, path));
    if (!file.startsWith(normalize(root + sep)) && file !== normalize(root)) {
      response.writeHead(403).end();
      return;
    }
    if (existsSync(file) && statSync(file).isDirectory()) file = join(file, 'index.html');
    if (!existsSync(file)) {
      response.writeHead(404).end('not found');
      return;
    }
    response.writeHead(200, {
      'Content-Type': MIME[extname(file)] ?? 'application/octet-stream',
      'Cache-Control': 'no-cache',
    });
    createReadStream(file).pipe(response);
  });
  await new Promise<void>((resolve, reject) => {
    server.once('error', reject);
    server.listen(port, host, () => resolve());
  });
  const address = server.address() as AddressInfo;
  return {
    url: `http://${host}:${address.port}/`,
    publish(data) {
      const path = `${TRANSFER}${nextId++}`;
      published.set(path, data);
      return path.slice(1);
    },
    close: () => new Promise((resolve) => server.close(() => resolve())),
  };
}
