#!/usr/bin/env node
// Bytes a player fetches when it streams by GOP over HTTP (web/js/gop_streamer.mjs) from the
// local server (web/tools/serve.mjs, ranges recorded): before the first frame (the range of
// the first GOP; of it, the bytes the decoder needs before the first frame comes out, pushed
// in 1 KB chunks), for a seek to the last frame from a fresh start, and the whole stream, for
// each STREAM (its GOP index is
// written beside a copy with build/release/tools/m4d_probe --gop-index). Prints a table.
//
//   node web/bench/gop_streaming.mjs STREAM...
import { execFileSync } from 'node:child_process';
import { copyFileSync, mkdtempSync, readFileSync, rmSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, join } from 'node:path';
import { fileURLToPath } from 'node:url';

import { GopStreamer } from '../js/gop_streamer.mjs';
import { serve } from '../tools/serve.mjs';

const streams = process.argv.slice(2);
if (streams.length === 0) {
  console.error('usage: gop_streaming.mjs STREAM...');
  process.exit(2);
}
const root = fileURLToPath(new URL('../../', import.meta.url));
const { loadM4d } = await import(new URL('build/web/module/m4d.mjs', `file://${root}`));
const m4d = await loadM4d();
const dir = mkdtempSync(join(tmpdir(), 'm4d-gop-bench-'));
const served = [];
const server = await serve(dir, 0, { onRequest: (log) => served.push(log) });
const base = `http://127.0.0.1:${server.address().port}`;
const streamBytes = (path, from) => served.slice(from).filter((r) => r.path === path).reduce((n, r) => n + r.bytes, 0);
const kb = (n) => (n / 1000).toFixed(1);

// Bytes pushed (1 KB at a time) before the decoder outputs the first frame.
function bytesForFirstFrame(data) {
  const decoder = m4d.openDecoder();
  try {
    for (let at = 0; at < data.length; ) {
      decoder.push(data.subarray(at, (at += 1024)));
      if (decoder.nextFrame()) return Math.min(at, data.length);
    }
    return data.length;
  } finally {
    decoder.close();
  }
}

console.log('| stream | KB | GOPs (random access) | frames | index KB | first frame: KB served | KB the decoder needs | ms | seek to last frame: KB served | KB skipped |');
console.log('|---|---|---|---|---|---|---|---|---|---|');
try {
  for (const stream of streams) {
    const name = basename(stream);
    copyFileSync(stream, join(dir, name));
    execFileSync(join(root, 'build/release/tools/m4d_probe'), ['--gop-index', join(dir, name), '-o', join(dir, `${name}.gops.json`)]);
    const size = statSync(stream).size;

    let from = served.length;
    const started = performance.now();
    const player = await GopStreamer.open({ m4d, url: `${base}/${name}`, readAhead: 0 });
    const indexBytes = player.bytesFetched;
    await player.nextFrame();
    const firstMs = performance.now() - started;
    const firstServed = streamBytes(`/${name}`, from);
    const needed = bytesForFirstFrame(readFileSync(stream));
    const { gops } = player.index;
    player.close();

    from = served.length;
    const seeker = await GopStreamer.open({ m4d, url: `${base}/${name}`, readAhead: 0 });
    const last = gops.at(-1).frame + gops.at(-1).frames - 1;
    seeker.seek(last);
    await seeker.nextFrame();
    const seekServed = streamBytes(`/${name}`, from);
    const skipped = gops[seeker.randomAccessGopOf(last)].offset;
    seeker.close();

    const ra = gops.filter((g) => g.random_access).length;
    console.log(`| ${name} | ${kb(size)} | ${gops.length} (${ra}) | ${player.frames} | ${kb(indexBytes)} | ${kb(firstServed)} | ${kb(needed)} | ${firstMs.toFixed(0)} | ${kb(seekServed)} | ${kb(skipped)} |`);
  }
} finally {
  server.close();
  rmSync(dir, { recursive: true, force: true });
}
