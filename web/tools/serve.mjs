#!/usr/bin/env node
// A static HTTP server for the web player: serves the repository (player, module, streams)
// on 127.0.0.1, read-only.
//
//   node web/tools/serve.mjs [--port 8080] [--root DIR]
//   then open http://127.0.0.1:8080/web/player/?stream=/out/default.m4d
import { createReadStream, statSync } from 'node:fs';
import { createServer } from 'node:http';
import { extname, join, normalize, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseArgs } from 'node:util';

const TYPES = {
  '.html': 'text/html; charset=utf-8', '.mjs': 'text/javascript', '.js': 'text/javascript',
  '.wasm': 'application/wasm', '.json': 'application/json', '.png': 'image/png',
  '.m4d': 'application/octet-stream', '.css': 'text/css',
};

// Serves files under `root`; resolves with the server once it listens (port 0: any free one).
export function serve(root, port = 0) {
  const base = resolve(root);
  const prefix = base.endsWith(sep) ? base : base + sep;
  const server = createServer((request, response) => {
    const path = decodeURIComponent(new URL(request.url, 'http://localhost').pathname);
    let file = normalize(join(base, path));
    if (file !== base && !file.startsWith(prefix)) {
      response.writeHead(403).end();
      return;
    }
    try {
      if (statSync(file).isDirectory()) file = join(file, 'index.html');
      const size = statSync(file).size;
      // Any origin may read (a page on another local port, e.g. a player fetching cameras).
      response.writeHead(200, {
        'Content-Type': TYPES[extname(file)] || 'application/octet-stream',
        'Content-Length': size,
        'Access-Control-Allow-Origin': '*',
      });
      createReadStream(file).pipe(response);
    } catch {
      response.writeHead(404).end();
    }
  });
  return new Promise((done) => server.listen(port, '127.0.0.1', () => done(server)));
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
  const { values } = parseArgs({ options: { port: { type: 'string', default: '8080' }, root: { type: 'string' } } });
  const root = values.root || fileURLToPath(new URL('../../', import.meta.url));
  const server = await serve(root, Number(values.port));
  console.log(`serving ${root} at http://127.0.0.1:${server.address().port}/web/player/`);
}
