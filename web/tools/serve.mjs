#!/usr/bin/env node
// A static HTTP server for the web player: serves the repository (player, module, streams)
// on 127.0.0.1, read-only, with HTTP range requests (GOP streaming, web/js/gop_streamer.mjs).
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

// The byte range a Range header asks of a file of `size` bytes: [start, end] inclusive, null
// without a header (the whole file), or 'invalid' (416) for one this server does not satisfy.
// One range only ("bytes=a-b", "bytes=a-", "bytes=-n"), as players ask.
export function parseRange(header, size) {
  if (header === undefined) return null;
  const m = /^bytes=(\d*)-(\d*)$/.exec(header.trim());
  if (!m || (m[1] === '' && m[2] === '')) return 'invalid';
  let start, end;
  if (m[1] === '') {  // the last n bytes
    const n = Number(m[2]);
    if (n === 0) return 'invalid';
    start = Math.max(0, size - n);
    end = size - 1;
  } else {
    start = Number(m[1]);
    end = m[2] === '' ? size - 1 : Math.min(Number(m[2]), size - 1);
  }
  if (start >= size || start > end) return 'invalid';
  return [start, end];
}

// Serves files under `root`; resolves with the server once it listens (port 0: any free one).
// Answers single Range requests (206 with Content-Range, 416 when unsatisfiable; Accept-Ranges
// on every file). `onRequest(log)` is called for each request answered, with { method, path,
// status, range: [start, end] or null, bytes: body bytes sent (or to be sent) }; tests record
// the ranges served with it.
export function serve(root, port = 0, { onRequest } = {}) {
  const base = resolve(root);
  const prefix = base.endsWith(sep) ? base : base + sep;
  const server = createServer((request, response) => {
    const path = decodeURIComponent(new URL(request.url, 'http://localhost').pathname);
    const log = (status, range, bytes) => {
      if (onRequest) onRequest({ method: request.method, path, status, range, bytes });
    };
    let file = normalize(join(base, path));
    if (file !== base && !file.startsWith(prefix)) {
      response.writeHead(403).end();
      log(403, null, 0);
      return;
    }
    try {
      if (statSync(file).isDirectory()) file = join(file, 'index.html');
      const size = statSync(file).size;
      // Any origin may read (a page on another local port, e.g. a player fetching cameras).
      const headers = {
        'Content-Type': TYPES[extname(file)] || 'application/octet-stream',
        'Accept-Ranges': 'bytes',
        'Access-Control-Allow-Origin': '*',
        'Access-Control-Expose-Headers': 'Content-Range, Content-Length, Accept-Ranges',
      };
      const range = parseRange(request.headers.range, size);
      if (range === 'invalid') {
        response.writeHead(416, { ...headers, 'Content-Range': `bytes */${size}` }).end();
        log(416, null, 0);
        return;
      }
      const [start, end] = range ?? [0, size - 1];
      const status = range ? 206 : 200;
      headers['Content-Length'] = size === 0 ? 0 : end - start + 1;
      if (range) headers['Content-Range'] = `bytes ${start}-${end}/${size}`;
      response.writeHead(status, headers);
      log(status, range, size === 0 ? 0 : end - start + 1);
      if (request.method === 'HEAD' || size === 0) {
        response.end();
        return;
      }
      createReadStream(file, { start, end }).pipe(response);
    } catch {
      response.writeHead(404).end();
      log(404, null, 0);
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
