#!/usr/bin/env node
// Per-frame cost of the PlayCanvas adapter in headless Chromium (WebGL2 on SwiftShader, the CPU
// rasterizer), beside the SDK's own WebGL2 renderer on the same frames and camera: for each
// frame of STREAM (main-thread decoder, frames copied into SplatFrames), the adapter's update
// (conversion and texture writes), PlayCanvas's first render after it (texture upload and draw,
// each timed until the GPU is done), the first render once its sorter (a worker) has answered,
// a render after that (draw only), then the SDK renderer's upload and draw (with its own
// split: project, sort, GL draw).
// Prints a table per frame and the medians; --screenshot PNG saves the example page's canvas.
//
//   node web/bench/playcanvas_frame_cost.mjs STREAM [--width 960] [--height 540] [--frames N]
//                                            [--cameras transforms.json --camera N] [--screenshot PNG]
import { parseArgs } from 'node:util';
import { fileURLToPath } from 'node:url';
import { relative, resolve } from 'node:path';
import puppeteer from 'puppeteer-core';
import { serve } from '../tools/serve.mjs';

const { values, positionals } = parseArgs({
  allowPositionals: true,
  options: {
    width: { type: 'string', default: '960' }, height: { type: 'string', default: '540' },
    frames: { type: 'string', default: '0' }, screenshot: { type: 'string' },
    cameras: { type: 'string' }, camera: { type: 'string' },
  },
});
if (positionals.length !== 1) {
  console.error('usage: playcanvas_frame_cost.mjs STREAM [--width W] [--height H] [--frames N] [--screenshot PNG]');
  process.exit(2);
}
// The stream is served from the file system root, the page from the repository (the example's
// import map names /web/node_modules/..., so the repository is the server's root).
const root = fileURLToPath(new URL('../../', import.meta.url));
const server = await serve(root);
const streams = await serve('/');
const base = `http://127.0.0.1:${server.address().port}`;
const browser = await puppeteer.launch({
  executablePath: process.env.M4D_CHROMIUM || '/usr/bin/chromium',
  headless: true,
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
  protocolTimeout: 0,  // large streams take minutes on SwiftShader
});
try {
  const page = await browser.newPage();
  page.on('pageerror', (e) => console.error(`page: ${e.message}`));
  await page.setViewport({ width: Number(values.width) + 20, height: Number(values.height) + 90 });
  const stream = `http://127.0.0.1:${streams.address().port}/${relative('/', resolve(positionals[0]))}`;
  await page.goto(`${base}/web/examples/playcanvas/?stream=${encodeURIComponent(stream)}&autoplay=0` +
    `&width=${values.width}&height=${values.height}` + (values.cameras ? `&cameras=${encodeURIComponent(
      `http://127.0.0.1:${streams.address().port}/${relative('/', resolve(values.cameras))}`)}&camera=${values.camera || 0}` : ''));
  await page.waitForFunction(() => window.m4dPlayCanvas && window.m4dPlayCanvas.state.frame, { timeout: 60000 });
  await page.evaluate(() => window.m4dPlayCanvas.loaded);
  const rows = await page.evaluate(async (limit) => {
    const { app, adapter, camera } = window.m4dPlayCanvas;
    const { SplatFrameMaker } = await import('/web/js/splat_frame.mjs');
    const { loadM4d } = await import('/build/web/module/m4d.mjs');
    const gl = app.graphicsDevice.gl;
    // The SDK renderer on a canvas of the same size, looking through the same camera.
    const m4d = await loadM4d();
    const own = document.createElement('canvas');
    own.id = 'own';
    own.width = app.graphicsDevice.width;
    own.height = app.graphicsDevice.height;
    document.body.appendChild(own);
    const renderer = m4d.openRenderer(own);
    const ownGl = own.getContext('webgl2');
    const sdkDecoder = m4d.openDecoder();
    // The page decodes in a worker for its PlayerCore; here two main-thread decoders of the
    // same bytes: one feeds the adapter (through SplatFrameMaker), one the SDK renderer.
    const bytes = new Uint8Array(await (await fetch(new URLSearchParams(location.search).get('stream'))).arrayBuffer());
    const decoder = m4d.openDecoder();
    decoder.push(bytes);
    decoder.end();
    const maker = new SplatFrameMaker();
    sdkDecoder.push(bytes);
    sdkDecoder.end();
    // The camera as the SDK takes it (world to camera, OpenCV axes) from the PlayCanvas entity.
    const w = camera.getWorldTransform().data, pos = camera.getPosition();
    const rotation = [w[0], w[4], w[8], -w[1], -w[5], -w[9], -w[2], -w[6], -w[10]];
    const translation = [0, 1, 2].map((r) => -(rotation[3 * r] * pos.x + rotation[3 * r + 1] * pos.y + rotation[3 * r + 2] * pos.z));
    const p = camera.camera.projectionMatrix.data, W = own.width, H = own.height;
    const sdkCamera = { fx: p[0] * W / 2, fy: p[5] * H / 2, cx: (1 - p[8]) * W / 2, cy: (1 + p[9]) * H / 2, rotation, translation };
    // The page's adapter (the page is paused: only this loop gives it frames); the example's
    // box is hidden while timing, so that both renderers draw the same splats only.
    const bench = adapter;
    if (window.m4dPlayCanvas.state.box) window.m4dPlayCanvas.state.box.enabled = false;
    let ready = 0;
    app.systems.gsplat.on('frame:ready', (_c, _l, isReady) => { if (isReady) ++ready; });
    const sorted = async () => { for (const seen = ready; ready < seen + 2;) await new Promise(requestAnimationFrame); };
    // Timed until the GPU (SwiftShader) is done: a one-pixel read waits for it.
    const pixel = new Uint8Array(4);
    // Both canvases' earlier work is drained first: they share Chromium's GPU thread.
    const drain = () => {
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
      ownGl.readPixels(0, 0, 1, 1, ownGl.RGBA, ownGl.UNSIGNED_BYTE, pixel);
    };
    const time = (f, context = gl) => {
      drain();
      const t0 = performance.now();
      f();
      context.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
      return performance.now() - t0;
    };
    const rows = [];
    for (let f; (f = decoder.nextFrame()) && (!limit || rows.length < limit);) {
      const frame = maker.make(f);
      const before = { ...bench.stats };
      const update = bench.update(frame);
      const uploadDraw = time(() => app.render());
      await sorted();  // PlayCanvas's sorter (a worker) has answered: the draw is of sorted splats
      const sortedDraw = time(() => app.render());
      const draw = time(() => app.render());
      const g = sdkDecoder.nextFrame();
      const sdkUpload = time(() => renderer.upload(sdkDecoder), ownGl);
      const sdkDraw = time(() => renderer.draw(sdkCamera), ownGl);
      const st = renderer.stats();
      rows.push({
        frame: f.frameIndex, key: f.isKeyframe, static: frame.static ? frame.static.count : -1,
        dynamic: frame.dynamic.count, rebuilt: (bench.stats.staticBuilds > before.staticBuilds ? 'S' : '') +
          (bench.stats.dynamicBuilds > before.dynamicBuilds ? 'D' : bench.stats.dynamicInPlace > before.dynamicInPlace ? 'd' : ''),
        update, uploadDraw, sortedDraw, draw, sdkUpload, sdkDraw, sdkFrame: g ? g.frameIndex : -1,
        sdkProject: st.projectMs, sdkSort: st.sortMs, sdkGl: st.drawMs,
      });
    }
    if (window.m4dPlayCanvas.state.box) window.m4dPlayCanvas.state.box.enabled = true;
    return rows;
  }, Number(values.frames));
  const f = (v) => v.toFixed(1).padStart(8);
  // built: S static entity rebuilt, D dynamic entity rebuilt, d dynamic updated in place.
  console.log('frame key  static dynamic built   update pc up+draw pc sorted  pc draw  sdk upload  sdk draw (project sort gl)');
  for (const r of rows) {
    console.log(`${String(r.frame).padStart(5)} ${r.key ? 'K' : ' '}  ${String(r.static).padStart(6)} ${String(r.dynamic).padStart(7)} ` +
      `${r.rebuilt.padEnd(5)} ${f(r.update)}  ${f(r.uploadDraw)}  ${f(r.sortedDraw)} ${f(r.draw)}    ${f(r.sdkUpload)}  ${f(r.sdkDraw)} (${r.sdkProject.toFixed(1)} ${r.sdkSort.toFixed(1)} ${r.sdkGl.toFixed(1)})`);
  }
  const median = (k, pick = () => true) => {
    const v = rows.filter(pick).map((r) => r[k]).sort((a, b) => a - b);
    return v.length ? v[v.length >> 1] : NaN;
  };
  for (const [name, pick] of [['all', undefined], ['key', (r) => r.key], ['inter', (r) => !r.key]]) {
    console.log(`median ${name.padEnd(5)} (${rows.filter(pick || (() => true)).length} frames): update ${median('update', pick).toFixed(1)} ms, ` +
      `PlayCanvas upload+draw ${median('uploadDraw', pick).toFixed(1)} ms, first sorted draw ${median('sortedDraw', pick).toFixed(1)} ms, draw ${median('draw', pick).toFixed(1)} ms; ` +
      `SDK upload ${median('sdkUpload', pick).toFixed(1)} ms, draw ${median('sdkDraw', pick).toFixed(1)} ms`);
  }
  if (values.screenshot) {
    await page.evaluate(() => window.m4dPlayCanvas.showFrame(0));
    await (await page.$('#view')).screenshot({ path: values.screenshot });
  }
} finally {
  await browser.close();
  server.close();
  streams.close();
}
