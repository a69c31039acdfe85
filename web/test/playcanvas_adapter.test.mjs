// Tests of the PlayCanvas adapter (web/adapters/playcanvas_adapter.mjs) in headless Chromium
// with the playcanvas package from npm, through its example page (web/examples/playcanvas/):
// it plays the default scene's stream, a frame seen from a capture camera is compared with
// the native renderer's image of it (m4d_play), and the static layer is not rebuilt on inter
// frames. Needs scripts/build.sh (m4d, m4d_play) and scripts/build_web.sh.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { copyFileSync, mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { serve } from '../tools/serve.mjs';
import { openPage, psnrAgainstPng as psnrOf, root, startChromium } from './chromium_harness.mjs';
import { checkWorkerPlayback } from './worker_playback_check.mjs';

let chromium;

before(async () => {
  chromium = await startChromium();
});

after(async () => {
  await chromium?.close();
});

// page.problems goes on gathering the errors thrown in the page later on.
async function openExample(query) {
  const page = await openPage(chromium.browser, `${chromium.base}/web/examples/playcanvas/?${query}`);
  await page.waitForFunction(() => window.m4dPlayCanvas && window.m4dPlayCanvas.state.frame, { timeout: 30000 });
  await page.evaluate(() => window.m4dPlayCanvas.loaded);
  assert.deepEqual(page.problems, []);
  return page;
}

// PSNR in dB of the example's canvas against a PNG (bytes).
const psnrAgainstPng = (page, png) => psnrOf(page, png, 'm4dPlayCanvas');

test('plays the default scene through PlayCanvas as m4d_play draws it', async (t) => {
  const stream = join(root, 'conformance/streams/enc_adaptive_gop.m4d');
  const dir = mkdtempSync(join(tmpdir(), 'm4d-playcanvas-'));
  const capture = join(dir, 'scene');
  const files = await serve(dir);
  try {
    // The conformance streams' scene (scripts/make_conformance.sh): its transforms.json.
    execFileSync(join(root, 'build/release/tools/m4d/m4d'), ['scene', '-o', capture, '--cameras', '6',
      '--width', '64', '--height', '48', '--frames', '6', '--points', '2000']);
    execFileSync(join(root, 'build/release/tools/m4d_play'), [stream, '--capture', capture, '--camera', '1',
      '--width', '320', '--height', '240', '--frames', '4', '-o', dir]);
    const cameras = `http://127.0.0.1:${files.address().port}/scene/transforms.json`;
    const page = await openExample(`stream=/conformance/streams/enc_adaptive_gop.m4d&width=320&height=240` +
      `&autoplay=0&cameras=${encodeURIComponent(cameras)}&camera=1`);
    // The box (an ordinary entity) is composited with the splats; hidden for the comparison.
    const withBox = await page.evaluate(async () => {
      await window.m4dPlayCanvas.showFrame(0);
      return window.m4dPlayCanvas.readRgb().reduce((a, b) => a + b, 0);
    });
    const withoutBox = await page.evaluate(async () => {
      window.m4dPlayCanvas.state.box.enabled = false;
      for (let i = 0; i < 2; ++i) await new Promise(requestAnimationFrame);
      return window.m4dPlayCanvas.readRgb().reduce((a, b) => a + b, 0);
    });
    assert.notEqual(withBox, withoutBox, 'the box changes the picture');
    const staticEntity = () => page.evaluate(() => window.m4dPlayCanvas.adapter.entities.static.getGuid());
    const reference = (frame) => readFileSync(join(dir, `frame_0000${frame}.png`));
    const guids = [], psnrs = [];
    for (const frame of [0, 1, 2, 3]) {  // keyframe, inter, keyframe, inter (GOPs of 2)
      assert.equal(await page.evaluate((f) => window.m4dPlayCanvas.showFrame(f), frame), frame);
      guids.push(await staticEntity());
      const psnr = await psnrAgainstPng(page, reference(frame));
      psnrs.push(psnr);
      t.diagnostic(`frame ${frame}: ${psnr.toFixed(2)} dB against m4d_play`);
      // Measured 33.9-34.5 dB (SwiftShader): PlayCanvas stores colours, scales and rotations
      // as half floats and SH as 11/10/11-bit fractions, sorts by distance along the view axis
      // in a worker, and its splat footprint and alpha cut-off differ from the SDK renderer's;
      // both write sRGB-encoded colours unchanged (PlayCanvas's default gamma output).
      assert.ok(psnr >= 31, `frame ${frame}: ${psnr.toFixed(2)} dB against m4d_play`);
    }
    // A different frame's image scores lower: the comparison sees the dynamic layer move.
    const other = await psnrAgainstPng(page, reference(0));
    // Frame 3's dynamic layer was updated in place: it matches frame 3's image clearly better
    // than frame 2's (same static layer; measured 34.45 against 31.32 dB).
    const previous = await psnrAgainstPng(page, reference(2));
    t.diagnostic(`frame 3 against frame 2's reference: ${previous.toFixed(2)} dB`);
    assert.ok(psnrs[3] - previous >= 1.5, `in place: ${psnrs[3].toFixed(2)} against ${previous.toFixed(2)} dB`);
    t.diagnostic(`frame 3 against frame 0's reference: ${other.toFixed(2)} dB`);
    assert.ok(other < 31, `frame 3 against frame 0's reference: ${other.toFixed(2)} dB`);
    // Inter frames keep the static entity; keyframes (which bring a new static layer) rebuild it.
    assert.equal(guids[1], guids[0]);
    assert.equal(guids[3], guids[2]);
    assert.notEqual(guids[2], guids[1]);
    const stats = await page.evaluate(() => window.m4dPlayCanvas.adapter.stats);
    t.diagnostic(JSON.stringify(stats));
    assert.ok(stats.dynamicInPlace >= 2, 'the dynamic layer is updated in place');
    // Bad input: a clear error.
    const errors = await page.evaluate(() => {
      const { adapter, app, pc } = window.m4dPlayCanvas;
      const message = (f) => { try { f(); return ''; } catch (e) { return `${e.name}: ${e.message}`; } };
      return [message(() => adapter.update(null)),
        message(() => adapter.update({ staticChanged: true, static: null, dynamic: null })),
        message(() => new adapter.constructor(app, {})),
        message(() => adapter.update({ staticChanged: false, static: null, dynamic: { count: 2, shDegree: 0,
          shCoefficients: 1, positions: new Float32Array(3), logScales: new Float32Array(6), rotations: new Float32Array(8),
          opacityLogits: new Float32Array(2), sh: new Float32Array(6) } }))];
    });
    for (const e of errors) assert.match(e, /^TypeError: M4dPlayCanvasAdapter/);
    assert.match(errors[3], /dynamic layer: positions must be a Float32Array of 6 values/);
    // destroy() takes both entities out of the scene.
    const left = await page.evaluate(() => {
      const { adapter, app } = window.m4dPlayCanvas;
      adapter.destroy();
      return app.root.children.filter((e) => e.name.startsWith('m4d-')).length;
    });
    assert.equal(left, 0);
    assert.deepEqual(page.problems, []);
    await page.close();
  } finally {
    files.close();
    rmSync(dir, { recursive: true, force: true });
  }
});

// The page decodes in a Web Worker paced by PlayerCore (worker_playback_check.mjs).
test('plays through the worker decoder at the stream fps, looping at the end', async () => {
  const page = await openExample('stream=/conformance/streams/enc_adaptive_gop.m4d&width=96&height=72');
  try {
    await checkWorkerPlayback(page, 'm4dPlayCanvas');
  } finally {
    await page.close();
  }
});

// gops=1: frames come through a GopStreamer (range requests by GOP) instead of the worker.
test('gops=1 plays by GOP with range requests only', async () => {
  const gopDir = mkdtempSync(join(tmpdir(), 'm4d-playcanvas-gops-'));
  const served = [];
  let gopServer;
  try {
    copyFileSync(join(root, 'conformance/streams/enc_adaptive_gop.m4d'), join(gopDir, 's.m4d'));
    execFileSync(join(root, 'build/release/tools/m4d_probe'), ['--gop-index', join(gopDir, 's.m4d'), '-o', join(gopDir, 's.m4d.gops.json')]);
    gopServer = await serve(gopDir, 0, { onRequest: (r) => served.push(r) });
    const url = `http://127.0.0.1:${gopServer.address().port}/s.m4d`;
    const page = await openExample(`stream=${encodeURIComponent(url)}&gops=1&width=96&height=72&autoplay=0`);
    try {
      assert.equal(await page.evaluate(() => window.m4dPlayCanvas.showFrame(3)), 3);
      const seen = await page.evaluate(() => ({
        source: window.m4dPlayCanvas.decoder.constructor.name, gops: window.m4dPlayCanvas.streamer.requests.map((r) => r.gop),
      }));
      assert.equal(seen.source, 'DecoderFrameSource');
      const ranges = served.filter((r) => r.path === '/s.m4d');
      assert.ok(ranges.length === seen.gops.length && ranges.every((r) => r.status === 206), JSON.stringify(ranges));
      assert.equal(new Set(seen.gops).size, seen.gops.length);
      assert.deepEqual(page.problems, []);
    } finally {
      await page.close();
    }
  } finally {
    gopServer?.close();
    rmSync(gopDir, { recursive: true, force: true });
  }
});
