#!/usr/bin/env node
// Playback of the adapters' example pages (web/examples/spark/, web/examples/playcanvas/) in
// headless Chromium (WebGL2 on SwiftShader): each page plays STREAM (looping) for --seconds
// through its frame source (the worker decoder, or with --gops a GopStreamer) paced by
// PlayerCore; the table gives the frames PlayerCore showed, dropped (decoding behind the clock),
// the stalls and resyncs, the page's drawn frames per second (requestAnimationFrame) and the
// median decode time (in the worker, or on the main thread by GOP).
//
//   node web/bench/example_playback.mjs [STREAM] [--seconds 5] [--width 320] [--height 240] [--gops]
import { execFileSync } from 'node:child_process';
import { copyFileSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { parseArgs } from 'node:util';
import { fileURLToPath } from 'node:url';
import puppeteer from 'puppeteer-core';
import { serve } from '../tools/serve.mjs';

const { values, positionals } = parseArgs({
  allowPositionals: true,
  options: {
    seconds: { type: 'string', default: '5' }, width: { type: 'string', default: '320' },
    height: { type: 'string', default: '240' }, gops: { type: 'boolean', default: false },
  },
});
const root = fileURLToPath(new URL('../../', import.meta.url));
const streamPath = resolve(positionals[0] || join(root, 'conformance/streams/enc_adaptive_gop.m4d'));
const dir = mkdtempSync(join(tmpdir(), 'm4d-playback-'));
copyFileSync(streamPath, join(dir, 's.m4d'));
if (values.gops) {
  execFileSync(join(root, 'build/release/tools/m4d_probe'), ['--gop-index', join(dir, 's.m4d'), '-o', join(dir, 's.m4d.gops.json')]);
}
const server = await serve(root);
const files = await serve(dir);
const stream = `http://127.0.0.1:${files.address().port}/s.m4d`;
const browser = await puppeteer.launch({
  executablePath: process.env.M4D_CHROMIUM || '/usr/bin/chromium',
  headless: true,
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});
const pages = [['three.js + Spark', 'spark', 'm4dSpark'], ['PlayCanvas', 'playcanvas', 'm4dPlayCanvas']];
const rows = [];
try {
  for (const [name, path, hook] of pages) {
    const page = await browser.newPage();
    page.on('pageerror', (e) => console.error(`${path}: ${e.message}`));
    await page.goto(`http://127.0.0.1:${server.address().port}/web/examples/${path}/?stream=${encodeURIComponent(stream)}` +
      `&width=${values.width}&height=${values.height}${values.gops ? '&gops=1' : ''}`);
    await page.waitForFunction((h) => window[h] && window[h].state.frame, { timeout: 60000 }, hook);
    await page.evaluate((h) => window[h].loaded, hook);
    rows.push({ name, ...await page.evaluate(async (h, ms) => {
      const { core, decoder } = window[h];
      const before = { ...core.stats };
      const decodes = [];
      let draws = 0, last = -1;
      const t0 = performance.now();
      while (performance.now() - t0 < ms) {
        await new Promise(requestAnimationFrame);
        ++draws;
        if (core.stats.shown !== last) { last = core.stats.shown; decodes.push(decoder.lastDecodeMs); }
      }
      const seconds = (performance.now() - t0) / 1000;
      decodes.sort((a, b) => a - b);
      const d = (k) => core.stats[k] - before[k];
      return { fps: decoder.streamInfo().fps, shown: d('shown'), dropped: d('dropped'), stalls: d('stalls'), resyncs: d('resyncs'),
        rafPerSecond: draws / seconds, decodeMs: decodes[decodes.length >> 1] ?? NaN, seconds };
    }, hook, 1000 * Number(values.seconds)) });
    await page.close();
  }
} finally {
  await browser.close();
  server.close();
  files.close();
  rmSync(dir, { recursive: true, force: true });
}
console.log(`stream ${streamPath.split('/').pop()}, ${values.width}x${values.height}, ${values.gops ? 'GopStreamer (main thread)' : 'M4dWorkerDecoder'}, ${values.seconds} s playing, Chromium SwiftShader`);
console.log('| page | stream fps | shown | shown/s | dropped | stalls | resyncs | rAF/s | decode ms (median) |');
console.log('|---|---|---|---|---|---|---|---|---|');
for (const r of rows) {
  console.log(`| ${r.name} | ${r.fps} | ${r.shown} | ${(r.shown / r.seconds).toFixed(1)} | ${r.dropped} | ${r.stalls} | ${r.resyncs} | ` +
    `${r.rafPerSecond.toFixed(1)} | ${r.decodeMs.toFixed(1)} |`);
}
