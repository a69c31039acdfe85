// A local HTTP server of a directory's files with HTTP Range support at a bandwidth the caller
// changes while it runs (state.rate, bytes per second), recording the ranges it serves: what
// the adaptive-bitrate test and bench play renditions from. It allows cross-origin requests
// (CORS), so that a page served by another server plays from it.
//
//   const server = await throttledServer(dir);   // server.base: 'http://127.0.0.1:PORT/'
//   server.rate = 50_000;                        // applies from the next request
//   ... server.served: [{ url, first, last }] ...
//   await server.close();
import { readFileSync } from 'node:fs';
import { createServer } from 'node:http';
import { join } from 'node:path';

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

// Starts the server on a free port of 127.0.0.1; resolves to its state.
export async function throttledServer(dir, { rate = 1e6, chunk = 512 } = {}) {
  const state = { rate, served: [], base: '', close: null };
  const server = createServer(async (req, res) => {
    // Cross-origin: a page served elsewhere fetches the manifest and its ranges.
    res.setHeader('Access-Control-Allow-Origin', '*');
    res.setHeader('Access-Control-Expose-Headers', 'Content-Range, Content-Length');
    if (req.method === 'OPTIONS') {
      res.writeHead(204, { 'Access-Control-Allow-Headers': 'Range', 'Access-Control-Max-Age': '600' }).end();
      return;
    }
    let data;
    try {
      const path = decodeURIComponent(new URL(req.url, 'http://x').pathname);
      if (path.split('/').includes('..')) throw new Error('outside');
      data = readFileSync(join(dir, path));
    } catch {
      res.writeHead(404).end();
      return;
    }
    let first = 0, last = data.length - 1, status = 200;
    const range = /^bytes=(\d+)-(\d+)$/.exec(req.headers.range || '');
    if (range) {
      first = Number(range[1]);
      last = Math.min(Number(range[2]), data.length - 1);
      if (first > last) {
        res.writeHead(416, { 'Content-Range': `bytes */${data.length}` }).end();
        return;
      }
      status = 206;
    }
    const body = data.subarray(first, last + 1);
    state.served.push({ url: req.url, first, last });
    res.writeHead(status, {
      'Content-Length': body.length,
      'Accept-Ranges': 'bytes',
      ...(status === 206 ? { 'Content-Range': `bytes ${first}-${last}/${data.length}` } : {}),
    });
    // Paced on the clock, not per chunk, so that timer slack does not add up.
    const bytesPerSecond = state.rate, start = performance.now();
    for (let at = 0; at < body.length; at += chunk) {
      res.write(body.subarray(at, at + chunk));
      const wait = start + ((at + chunk) / bytesPerSecond) * 1000 - performance.now();
      if (wait > 0) await sleep(wait);
    }
    res.end();
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  state.base = `http://127.0.0.1:${server.address().port}/`;
  state.close = () => new Promise((resolve) => server.close(resolve));
  return state;
}
