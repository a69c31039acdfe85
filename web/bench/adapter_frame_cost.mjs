#!/usr/bin/env node
// Per-frame cost of showing an M4D stream in headless Chromium (WebGL2 on SwiftShader, the
// CPU rasterizer), one row per viewer: the frames of STREAM are shown one after another from
// the same camera, and each stage is timed per frame; the table prints the median and the
// maximum over the frames.
//
//   node web/bench/adapter_frame_cost.mjs [STREAM] [--width 640] [--height 480] [--frames N]
//                                         [--rows spark,player] [--screenshot-spark PNG]
//
// Columns (ms per frame): decode (for Spark: in the worker, M4dWorkerDecoder.lastDecodeMs,
// off the main thread; for the player: m4d.mjs on the main thread), copy (Spark: the rest of
// the worker round trip: the SplatFrame's copies, the message and its transfer), update (the adapter's update(): packing
// and marking buffers for upload; the player's upload), engine (the engine's own per-frame
// work before drawing: Spark generates its splat textures on the GPU, reads depths back and
// sorts in a worker), draw (render() then gl.finish(), so the GPU work is counted).
//
// A row is a { name, url(query), measure } entry of ROWS: `measure` runs in the page and
// returns per-frame stage times; another viewer (e.g. the PlayCanvas adapter's example page,
// same update(splatFrame) API) is added as one more entry.
import { parseArgs } from 'node:util';
import { dirname, basename, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import puppeteer from 'puppeteer-core';
import { serve } from '../tools/serve.mjs';

const { values, positionals } = parseArgs({
  allowPositionals: true,
  options: {
    width: { type: 'string', default: '640' }, height: { type: 'string', default: '480' },
    frames: { type: 'string', default: '0' }, rows: { type: 'string', default: 'spark,player' },
    'screenshot-spark': { type: 'string' },
  },
});
const root = fileURLToPath(new URL('../../', import.meta.url));
const streamPath = resolve(positionals[0] || resolve(root, 'conformance/streams/enc_adaptive_gop.m4d'));
const width = Number(values.width), height = Number(values.height);

// In-page measurement of the Spark example page (web/examples/spark/): window.m4dSpark.
async function measureSpark(frames) {
  const s = window.m4dSpark;
  const gl = s.renderer.getContext();
  const times = [];
  const idle = async () => {
    while (s.sparkRenderer.sorting || s.sparkRenderer.sortDirty) {
      await new Promise((done) => setTimeout(done, 1));
      await s.sparkRenderer.driveSort();
    }
  };
  // A worker decoder of its own (the page's feeds its PlayerCore), over the page's stream.
  const { M4dWorkerDecoder } = await import('/web/js/worker_decoder.mjs');
  const decoder = new M4dWorkerDecoder({ moduleUrl: '/build/web/module/m4d.mjs' });
  await decoder.open();
  const stream = new URLSearchParams(location.search).get('stream');
  await decoder.push(new Uint8Array(await (await fetch(stream)).arrayBuffer()), { transfer: true });
  await decoder.end();
  await s.settle();
  for (let f = 0; f < frames; ++f) {
    let t = performance.now();
    const splatFrame = await decoder.nextFrame();
    if (!splatFrame) break;
    const decode = decoder.lastDecodeMs;
    const copy = performance.now() - t - decode;
    t = performance.now();
    s.adapter.update(splatFrame);
    const update = performance.now() - t;
    await idle();
    t = performance.now();
    await s.sparkRenderer.update({ scene: s.scene, camera: s.camera });
    await idle();
    const engine = performance.now() - t;
    t = performance.now();
    s.renderer.render(s.scene, s.camera);
    gl.finish();
    const draw = performance.now() - t;
    times.push({ decode, copy, update, engine, draw, splats: splatFrame.dynamic.count + s.adapter.stats.staticCount,
      staticUpload: splatFrame.staticChanged });
  }
  decoder.close();
  return times;
}

// Our own player (web/player/, window.m4dPlayer): its decode time, then the SDK renderer's
// stages for the frame's draw: upload (of the projected splats to WebGL), engine (project and
// sort on the CPU, in WebAssembly), draw (WebGL draw then glFinish).
async function measurePlayer(frames) {
  const p = window.m4dPlayer;
  const times = [];
  for (let f = 0; f < frames; ++f) {
    await p.showFrame((p.state.firstIndex + f) >>> 0);
    const stats = p.renderStats();
    times.push({ decode: p.state.decodeMs, copy: 0, update: stats.uploadMs, engine: stats.projectMs + stats.sortMs,
      draw: stats.drawMs, splats: stats.visible, staticUpload: false });
  }
  return times;
}

const ROWS = {
  spark: {
    name: 'three.js + Spark (M4dSparkAdapter)',
    url: (q) => `/web/examples/spark/?${q}&mesh=0`,
    ready: () => window.m4dSpark && window.m4dSpark.state.frame,
    measure: measureSpark,
  },
  player: {
    name: 'M4D player (WebGL2, SDK renderer)',
    url: (q) => `/web/player/?${q}`,
    ready: () => window.m4dPlayer && window.m4dPlayer.state.frame,
    measure: measurePlayer,
  },
};

const server = await serve(root);
const files = await serve(dirname(streamPath));
const base = `http://127.0.0.1:${server.address().port}`;
const streamUrl = `http://127.0.0.1:${files.address().port}/${encodeURIComponent(basename(streamPath))}`;
const browser = await puppeteer.launch({
  executablePath: process.env.M4D_CHROMIUM || '/usr/bin/chromium',
  headless: true,
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});
const median = (a) => { const s = [...a].sort((x, y) => x - y); return s.length ? s[s.length >> 1] : NaN; };
const results = [];
try {
  for (const key of values.rows.split(',')) {
    const row = ROWS[key];
    if (!row) throw new Error(`unknown row ${key} (rows: ${Object.keys(ROWS).join(', ')})`);
    const page = await browser.newPage();
    page.on('pageerror', (e) => console.error(`${key}: ${e.message}`));
    await page.setViewport({ width: width + 20, height: height + 60 });
    await page.goto(`${base}${row.url(`stream=${encodeURIComponent(streamUrl)}&width=${width}&height=${height}&autoplay=0`)}`);
    await page.waitForFunction(row.ready, { timeout: 60000 });
    await page.evaluate(() => (window.m4dSpark || window.m4dPlayer).loaded);
    const frames = Number(values.frames) || await page.evaluate(() => (window.m4dSpark || window.m4dPlayer).decoder.streamInfo().numFrames);
    const times = await page.evaluate(`(${row.measure.toString()})(${frames})`);
    results.push({ name: row.name, times });
    if (key === 'spark' && values['screenshot-spark']) {
      await page.evaluate(() => window.m4dSpark.settle());
      await page.screenshot({ path: values['screenshot-spark'], clip: { x: 0, y: 0, width: width + 16, height: height + 40 } });
    }
    await page.close();
  }
} finally {
  await browser.close();
  server.close();
  files.close();
}

console.log(`stream ${basename(streamPath)}, ${width}x${height}, Chromium (WebGL2 on SwiftShader); ms per frame, median (max)`);
console.log('| viewer | frames | splats | decode | copy | update/upload | engine | draw | update+engine+draw |');
console.log('|---|---|---|---|---|---|---|---|---|');
for (const { name, times } of results) {
  const col = (f) => `${median(times.map(f)).toFixed(2)} (${Math.max(...times.map(f)).toFixed(2)})`;
  console.log(`| ${name} | ${times.length} | ${median(times.map((t) => t.splats))} | ${col((t) => t.decode)} | ${col((t) => t.copy)} | ` +
    `${col((t) => t.update)} | ${col((t) => t.engine)} | ${col((t) => t.draw)} | ${col((t) => t.update + t.engine + t.draw)} |`);
}
