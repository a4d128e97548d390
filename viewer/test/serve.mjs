// A tiny static file server for the browser tests, on 127.0.0.1 only.
//   GET /PATH                          ROOT/PATH (index.html for a directory)
//   GET /api/sessions/ID/scene.glb     ROOT/sessions/ID.glb, as the C++ server's session route;
//                                      with a token set, only with `Authorization: Bearer TOKEN`.
// Usage: node test/serve.mjs --root DIR [--port N] [--token TOKEN]   (or import serve()).
import { createServer } from 'node:http';
import { readFile, stat } from 'node:fs/promises';
import { extname, join, normalize, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';

const TYPES = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.json': 'application/json',
  '.glb': 'model/gltf-binary',
  '.png': 'image/png',
  '.css': 'text/css',
};

/** Starts the server; resolves to {url, port, close(), requests} (requests: [{method, path, authorization}]). */
export function serve({ root, port = 0, token = null }) {
  const base = resolve(root);
  const requests = [];
  const server = createServer(async (request, response) => {
    const url = new URL(request.url, 'http://127.0.0.1');
    requests.push({ method: request.method, path: url.pathname, authorization: request.headers.authorization || null });
    const send = (status, body, type = 'text/plain; charset=utf-8') => {
      response.writeHead(status, { 'Content-Type': type, 'Cache-Control': 'no-store' });
      response.end(body);
    };
    if (request.method !== 'GET' && request.method !== 'HEAD') return send(405, 'method not allowed\n');
    let path;
    const session = /^\/api\/sessions\/([A-Za-z0-9_-]+)\/scene\.glb$/.exec(url.pathname);
    if (session) {
      if (token && request.headers.authorization !== `Bearer ${token}`) return send(401, 'unauthorized\n');
      path = join(base, 'sessions', `${session[1]}.glb`);
    } else {
      let relative;
      try {
        relative = normalize(decodeURIComponent(url.pathname)).replace(/^[/\\]+/, '');
      } catch {
        return send(400, 'bad path\n');
      }
      path = join(base, relative);
      if (path !== base && !path.startsWith(base + sep)) return send(403, 'forbidden\n');
    }
    try {
      if ((await stat(path)).isDirectory()) path = join(path, 'index.html');
      const body = await readFile(path);
      send(200, request.method === 'HEAD' ? undefined : body, TYPES[extname(path)] || 'application/octet-stream');
    } catch {
      send(404, 'not found\n');
    }
  });
  return new Promise((resolvePromise, reject) => {
    server.once('error', reject);
    server.listen(port, '127.0.0.1', () => {
      const actual = server.address().port;
      resolvePromise({
        url: `http://127.0.0.1:${actual}`,
        port: actual,
        requests,
        close: () => new Promise((done) => server.close(() => done())),
      });
    });
  });
}

if (process.argv[1] && resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const option = (name, fallback) => {
    const i = process.argv.indexOf(name);
    return i >= 0 && i + 1 < process.argv.length ? process.argv[i + 1] : fallback;
  };
  const server = await serve({ root: option('--root', '.'), port: Number(option('--port', '0')), token: option('--token', null) });
  console.log(`serving ${resolve(option('--root', '.'))} at ${server.url}`);
}
