#!/usr/bin/env node
// The decoder on the page's thread against the decoder in a Web Worker (web/js/worker_decoder.mjs),
// in headless Chromium: per keyframe and per inter frame, milliseconds to decode on the page's
// thread, to decode and copy into a SplatFrame there, and for a worker's nextFrame() round trip
// (decode, copy, transfer), with the worker's own decode + copy time ("worker d+c") and the
// megabytes transferred.
// Averages over every frame of STREAM, best of --runs whole passes. STREAM must lie inside the
// repository (it is served from there).
//
//   node web/bench/worker_decoder.mjs STREAM... [--runs 3]
import { relative, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseArgs } from 'node:util';
import puppeteer from 'puppeteer-core';
import { serve } from '../tools/serve.mjs';

const { values, positionals } = parseArgs({ allowPositionals: true, options: { runs: { type: 'string', default: '3' } } });
if (positionals.length === 0) {
  console.error('usage: worker_decoder.mjs STREAM... [--runs N]');
  process.exit(2);
}
const root = fileURLToPath(new URL('../../', import.meta.url));
const server = await serve(root);
const browser = await puppeteer.launch({ executablePath: process.env.M4D_CHROMIUM || '/usr/bin/chromium', headless: true, args: ['--no-sandbox'] });
try {
  const page = await browser.newPage();
  page.on('pageerror', (e) => console.error(`page: ${e.message}`));
  await page.goto(`http://127.0.0.1:${server.address().port}/web/test/pages/worker_decoder.html`);
  await page.waitForFunction(() => window.m4dTest, { timeout: 30000 });
  console.log(`${'stream'.padEnd(26)} ${'frames'.padEnd(10)} ${'page decode'.padStart(12)} ${'page +copy'.padStart(11)} ` +
    `${'worker trip'.padStart(12)} ${'worker d+c'.padStart(11)} ${'MB moved'.padStart(9)}`);
  for (const stream of positionals) {
    const path = relative(root, resolve(stream));
    if (path.startsWith('..')) throw new Error(`${stream} is not inside the repository`);
    const rows = await page.evaluate(async (url, runs) => {
      const { loadM4d, M4dWorkerDecoder } = window.m4dTest;
      const { splatFrameFromDecoder, layersEqual, copySplatLayer } = await import('/web/js/splat_frame.mjs');
      const bytes = new Uint8Array(await (await fetch(url)).arrayBuffer());
      const m4d = await loadM4d();
      const best = {};
      const keep = (kind, name, value) => {
        const k = (best[kind] ??= {});
        k[name] = Math.min(k[name] ?? Infinity, value);
      };
      const average = (list) => list.reduce((a, b) => a + b, 0) / Math.max(list.length, 1);
      for (let run = 0; run < runs; ++run) {
        for (const copy of [false, true]) {
          const decoder = m4d.openDecoder();
          decoder.push(bytes);
          decoder.end();
          const times = { key: [], inter: [] };
          let lastStatic = null;
          for (;;) {
            const t0 = performance.now();
            const f = decoder.nextFrame();
            if (!f) break;
            if (copy) {
              const changed = !lastStatic || (f.isKeyframe && !layersEqual(f.static, lastStatic));
              splatFrameFromDecoder(f, { staticChanged: changed });
              if (changed) lastStatic = copySplatLayer(f.static);
            }
            times[f.isKeyframe ? 'key' : 'inter'].push(performance.now() - t0);
          }
          decoder.close();
          for (const kind of ['key', 'inter']) keep(kind, copy ? 'copy' : 'decode', average(times[kind]));
        }
        const worker = new M4dWorkerDecoder({ moduleUrl: '/build/web/module/m4d.mjs' });
        await worker.open();
        await worker.push(bytes);
        await worker.end();
        const trips = { key: [], inter: [] }, decodes = { key: [], inter: [] }, moved = { key: [], inter: [] };
        for (;;) {
          const t0 = performance.now();
          const f = await worker.nextFrame();
          if (!f) break;
          const kind = f.isKeyframe ? 'key' : 'inter';
          trips[kind].push(performance.now() - t0);
          decodes[kind].push(worker.lastDecodeMs);
          let size = 0;
          for (const layer of [f.static, f.dynamic]) {
            if (layer) for (const a of [layer.positions, layer.logScales, layer.rotations, layer.opacityLogits, layer.sh]) size += a.byteLength;
          }
          moved[kind].push(size / 1e6);
        }
        worker.close();
        for (const kind of ['key', 'inter']) {
          keep(kind, 'trip', average(trips[kind]));
          keep(kind, 'worker', average(decodes[kind]));
          keep(kind, 'mb', average(moved[kind]));
          keep(kind, 'count', trips[kind].length);
        }
      }
      return best;
    }, `/${path}`, Number(values.runs));
    for (const kind of ['key', 'inter']) {
      const r = rows[kind];
      if (!r || !r.count) continue;
      console.log(`${path.split('/').pop().replace(/\.m4d$/, '').padEnd(26)} ${`${kind} x${r.count}`.padEnd(10)} ` +
        `${r.decode.toFixed(2).padStart(12)} ${r.copy.toFixed(2).padStart(11)} ${r.trip.toFixed(2).padStart(12)} ` +
        `${r.worker.toFixed(2).padStart(11)} ${r.mb.toFixed(2).padStart(9)}`);
    }
  }
} finally {
  await browser.close();
  server.close();
}
