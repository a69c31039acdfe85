// Tests of the decoder in a Web Worker (web/js/m4d_worker.mjs, worker_decoder.mjs) in headless
// Chromium, the repository served from 127.0.0.1 as in player.test.mjs: every frame it sends
// matches the main-thread decoder's, the static layer is sent on the first frame and when it
// changes but not on inter frames, seeking, errors forwarded, a dead worker rejects calls.
// Needs scripts/build_web.sh; M4D_CHROMIUM names another browser binary.
import assert from 'node:assert/strict';
import { after, before, test } from 'node:test';
import { fileURLToPath } from 'node:url';
import puppeteer from 'puppeteer-core';
import { serve } from '../tools/serve.mjs';

const root = fileURLToPath(new URL('../../', import.meta.url));
const chromium = process.env.M4D_CHROMIUM || '/usr/bin/chromium';
let server, browser, page;
const problems = [];

before(async () => {
  server = await serve(root);
  browser = await puppeteer.launch({ executablePath: chromium, headless: true, args: ['--no-sandbox'] });
  page = await browser.newPage();
  page.on('pageerror', (e) => problems.push(e.message));
  await page.goto(`http://127.0.0.1:${server.address().port}/web/test/pages/worker_decoder.html`);
  await page.waitForFunction(() => window.m4dTest, { timeout: 15000 });
});

after(async () => {
  await browser?.close();
  server?.close();
});

test('frames from the worker match the main-thread decoder; static layer sent only on change', async () => {
  const result = await page.evaluate(async (url) => {
    const { loadM4d, M4dWorkerDecoder, copySplatLayer, layersEqual } = window.m4dTest;
    const bytes = new Uint8Array(await (await fetch(url)).arrayBuffer());
    // The reference: the main-thread decoder, every frame's layers copied.
    const m4d = await loadM4d();
    const main = m4d.openDecoder();
    main.push(bytes);
    main.end();
    const reference = new Map();
    for (let f; (f = main.nextFrame()); ) {
      reference.set(f.frameIndex, { isKeyframe: f.isKeyframe, static: copySplatLayer(f.static), dynamic: copySplatLayer(f.dynamic) });
    }
    main.close();

    const decoder = new M4dWorkerDecoder({ moduleUrl: '/build/web/module/m4d.mjs' });
    const { version } = await decoder.open();
    const frames = [];
    const mismatches = [];
    let held = null;  // the static layer the page holds
    const check = (frame) => {
      const expected = reference.get(frame.frameIndex);
      if (frame.staticChanged) held = frame.static;
      const owned = [frame.dynamic.positions, frame.dynamic.sh, held.positions].every(
        (a) => a.byteOffset === 0 && a.buffer.byteLength === a.byteLength);
      if (!layersEqual(frame.dynamic, expected.dynamic)) mismatches.push(`${frame.frameIndex} dynamic`);
      if (!layersEqual(held, expected.static)) mismatches.push(`${frame.frameIndex} static`);
      if (!owned) mismatches.push(`${frame.frameIndex} not owned`);
      if (frame.isKeyframe !== expected.isKeyframe) mismatches.push(`${frame.frameIndex} keyframe`);
      frames.push({ index: frame.frameIndex, keyframe: frame.isKeyframe, staticChanged: frame.staticChanged, staticSent: frame.static !== null });
    };
    // The stream in three chunks, frames drained as they come.
    const third = Math.ceil(bytes.length / 3);
    const detached = [];
    for (let at = 0; at < bytes.length; at += third) {
      // The first chunk is copied (a view of the whole stream), the others moved.
      const chunk = at === 0 ? bytes.subarray(0, third) : bytes.slice(at, at + third);
      await decoder.push(chunk, { transfer: at > 0 });
      detached.push(chunk.byteLength === 0);
      for (let f; (f = await decoder.nextFrame()); ) check(f);
    }
    await decoder.end();
    for (let f; (f = await decoder.nextFrame()); ) check(f);
    const ended = decoder.ended;
    const fps = decoder.streamInfo().fps;
    // Seek to an inter frame: it comes first, with its static layer.
    const sought = [];
    for (const target of [3, 1]) {
      if (!(await decoder.seek(target))) sought.push('refused');
      const f = await decoder.nextFrame();
      check(f);
      sought.push({ index: f.frameIndex, staticChanged: f.staticChanged });
    }
    const next = await decoder.nextFrame();
    check(next);
    sought.push({ index: next.frameIndex, staticChanged: next.staticChanged });
    // Errors come back as rejections, and the worker stays usable.
    const errors = [];
    for (const call of [() => decoder.seek(-1), () => decoder.push(new Uint8Array(4))]) {
      try { await call(); errors.push('no error'); } catch (e) { errors.push(e.message); }
    }
    const still = await decoder.seek(0);
    decoder.close();
    let closed;
    try { await decoder.nextFrame(); closed = 'no error'; } catch (e) { closed = e.message; }
    return { version, frames, mismatches, ended, fps, sought, errors, still, closed, detached, whole: bytes.byteLength };
  }, '/conformance/streams/enc_adaptive_gop.m4d');
  assert.match(result.version, /^\d+\.\d+\.\d+$/);
  assert.deepEqual(result.mismatches, []);
  assert.deepEqual(result.frames.slice(0, 6).map((f) => f.index), [0, 1, 2, 3, 4, 5]);
  // Frame 0 sends the static layer; inter frames never do; the dependent keyframes 2 and 4 do,
  // as their STATIC_UPDATE changes it.
  for (const f of result.frames.slice(0, 6)) {
    assert.equal(f.staticChanged, f.keyframe, `frame ${f.index}`);
    assert.equal(f.staticSent, f.staticChanged, `frame ${f.index}`);
  }
  assert.equal(result.ended, true);
  assert.equal(result.fps, 30);
  assert.deepEqual(result.detached, [false, true, true]);
  assert.ok(result.whole > 0);
  assert.deepEqual(result.sought, [{ index: 3, staticChanged: true }, { index: 1, staticChanged: true }, { index: 2, staticChanged: true }]);
  assert.match(result.errors[0], /bad frame -1/);
  assert.match(result.errors[1], /push after end/);
  assert.equal(result.still, true);
  assert.match(result.closed, /closed/);
  assert.deepEqual(problems, []);
});

test('the player core plays and seeks the worker decoder\'s frames', async () => {
  const result = await page.evaluate(async (url) => {
    const { M4dWorkerDecoder, PlayerCore } = window.m4dTest;
    const decoder = new M4dWorkerDecoder({ moduleUrl: '/build/web/module/m4d.mjs' });
    await decoder.open();
    await decoder.push(await (await fetch(url)).arrayBuffer());
    await decoder.end();
    const core = new PlayerCore(decoder);
    core.play();
    // Time advances one frame (at the stream's 30 fps) per frame shown: no frame is late.
    const shown = [];
    let now = 0;
    const nextShown = async () => {
      for (let polls = 0; polls < 2000; ++polls) {
        const f = core.tick(now);
        if (f) return f;
        if (core.ended || core.error) return null;
        await new Promise((done) => setTimeout(done, 1));
      }
      return null;
    };
    for (let f; (f = await nextShown()); now += 1000 / 30 + 0.001) {
      shown.push({ index: f.frameIndex, staticSent: f.static !== null });
    }
    const ended = core.ended;
    await core.seek(3);
    const sought = await nextShown();
    decoder.close();
    return { shown, ended, stats: core.stats, fps: core.fps, sought: { index: sought.frameIndex, staticSent: sought.static !== null } };
  }, '/conformance/streams/enc_adaptive_gop.m4d');
  assert.deepEqual(result.shown.map((f) => f.index), [0, 1, 2, 3, 4, 5]);
  assert.deepEqual(result.shown.map((f) => f.staticSent), [true, false, true, false, true, false]);
  assert.equal(result.ended, true);
  assert.equal(result.fps, 30);
  assert.deepEqual(result.stats, { shown: 7, dropped: 0, stalls: 0, resyncs: 0 });
  assert.deepEqual(result.sought, { index: 3, staticSent: true });
});

test('damage met by the worker is reported with the frames', async () => {
  const result = await page.evaluate(async (url) => {
    // The wasm named in the init message, fetched by the worker.
    const decoder = new window.m4dTest.M4dWorkerDecoder({ moduleUrl: '/build/web/module/m4d.mjs', wasmUrl: '/build/web/module/m4d_wasm.wasm' });
    await decoder.open();
    await decoder.push(await (await fetch(url)).arrayBuffer());
    await decoder.end();
    const frames = [];
    for (let f; (f = await decoder.nextFrame()); ) frames.push([f.frameIndex, f.concealedLayers]);
    decoder.close();
    return { frames, errors: decoder.errors };
  }, '/conformance/invalid/entropy_rans_damaged.m4d');
  // Frame 1's motion grid is damaged: the dynamic layer (bit 2) of frames 1 and 2 is concealed
  // until the next GOP (3); every frame is still output.
  assert.deepEqual(result.frames, [[0, 0], [1, 2], [2, 2], [3, 0], [4, 0], [5, 0]]);
  assert.ok(result.errors.count >= 1);
  assert.equal(result.errors.firstCodeName, 'M4D_ERR_BITSTREAM');
});

test('a worker that dies rejects the calls waiting and those after', async () => {
  const result = await page.evaluate(async () => {
    const { M4dWorkerDecoder } = window.m4dTest;
    const outcome = async (promise) => {
      try { await promise; return 'resolved'; } catch (e) { return e.message; }
    };
    // A script that is not there, and one that throws as it loads.
    const missing = new M4dWorkerDecoder({ workerUrl: '/web/test/pages/no_such_worker.mjs' });
    const broken = new M4dWorkerDecoder({
      workerUrl: URL.createObjectURL(new Blob(['throw new Error("boom");'], { type: 'text/javascript' })),
    });
    const opened = await Promise.all([outcome(missing.open()), outcome(broken.open())]);
    const later = await outcome(broken.nextFrame());
    // A worker that dies while a request waits (it never answers, then throws).
    const dying = new M4dWorkerDecoder({
      workerUrl: URL.createObjectURL(new Blob(['onmessage = () => setTimeout(() => { throw new Error("died"); }, 50);'], { type: 'text/javascript' })),
    });
    const waiting = await outcome(dying.open());
    return { opened, later, waiting };
  });
  assert.match(result.opened[0], /worker/);
  assert.match(result.opened[1], /boom|worker died/);
  assert.match(result.later, /boom|worker died/);
  assert.match(result.waiting, /died/);
});
