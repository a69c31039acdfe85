#!/usr/bin/env node
// Frames per second of the web player in headless Chromium (WebGL2 on SwiftShader, the CPU
// rasterizer): plays STREAM at WIDTHxHEIGHT for SECONDS and prints "<fps> <render ms>
// <decode ms> <splats> <project ms> <sort ms> <gl draw ms>" (render: the SDK renderer's whole
// draw; decode: the last frame's; then the draw's stages). --screenshot PNG saves the page.
//
//   node web/bench/player_fps.mjs STREAM [--width 1280] [--height 720] [--seconds 10]
//                                 [--cameras transforms.json --camera N] [--screenshot PNG]
import { parseArgs } from 'node:util';
import { fileURLToPath } from 'node:url';
import { relative, resolve } from 'node:path';
import puppeteer from 'puppeteer-core';
import { serve } from '../tools/serve.mjs';

const { values, positionals } = parseArgs({
  allowPositionals: true,
  options: {
    width: { type: 'string', default: '1280' }, height: { type: 'string', default: '720' },
    seconds: { type: 'string', default: '10' }, screenshot: { type: 'string' },
    cameras: { type: 'string' }, camera: { type: 'string' },
  },
});
if (positionals.length !== 1) {
  console.error('usage: player_fps.mjs STREAM [--width W] [--height H] [--seconds S] [--screenshot PNG]');
  process.exit(2);
}
// The stream is served from the file system root, the player from the repository.
const root = fileURLToPath(new URL('../../', import.meta.url));
const server = await serve('/');
const base = `http://127.0.0.1:${server.address().port}`;
const browser = await puppeteer.launch({
  executablePath: process.env.M4D_CHROMIUM || '/usr/bin/chromium',
  headless: true,
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});
try {
  const page = await browser.newPage();
  page.on('pageerror', (e) => console.error(`page: ${e.message}`));
  page.on('console', (m) => m.type() === 'error' && console.error(`page: ${m.text()}`));
  await page.setViewport({ width: Number(values.width) + 20, height: Number(values.height) + 90 });
  const stream = `/${relative('/', resolve(positionals[0]))}`;
  const module = `/${relative('/', resolve(root, 'build/web/module'))}/`;
  await page.goto(`${base}/${relative('/', resolve(root, 'web/player'))}/?stream=${stream}&module=${module}` +
    `&width=${values.width}&height=${values.height}` +
    (values.cameras ? `&cameras=/${relative('/', resolve(values.cameras))}&camera=${values.camera || 0}` : ''));
  await page.waitForFunction(() => window.m4dPlayer && window.m4dPlayer.state.frame, { timeout: 60000 });
  await page.evaluate(() => window.m4dPlayer.loaded);
  const count = () => page.evaluate(() => window.m4dPlayer.state.framesShown);
  const start = await count(), t0 = Date.now();
  await new Promise((done) => setTimeout(done, 1000 * Number(values.seconds)));
  const drawn = (await count()) - start, seconds = (Date.now() - t0) / 1000;
  const s = await page.evaluate(() => ({ render: window.m4dPlayer.state.renderMs, decode: window.m4dPlayer.state.decodeMs }));
  const r = await page.evaluate(() => window.m4dPlayer.renderStats());
  console.log(`${(drawn / seconds).toFixed(2)} ${s.render.toFixed(1)} ${s.decode.toFixed(1)} ${r.visible} ` +
    `${r.projectMs.toFixed(1)} ${r.sortMs.toFixed(1)} ${r.uploadMs.toFixed(1)} ${r.drawMs.toFixed(1)}`);
  if (values.screenshot) await page.screenshot({ path: values.screenshot });
} finally {
  await browser.close();
  server.close();
}
