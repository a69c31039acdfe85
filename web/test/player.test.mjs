// Tests of the web player (web/player/) in headless Chromium (Debian's chromium, driven with
// puppeteer-core over the DevTools protocol), served from 127.0.0.1: a frame it draws
// against the native renderer's image of the same frame and camera (m4d_play), and a damaged
// stream. Needs scripts/build.sh (m4d_play) and scripts/build_web.sh; M4D_CHROMIUM names
// another browser binary.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { createServer } from 'node:http';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { serve } from '../tools/serve.mjs';
import { openPage, psnrAgainstPng as psnrOf, root, startChromium } from './chromium_harness.mjs';

let chromium;

before(async () => {
  chromium = await startChromium();
});

after(async () => {
  await chromium?.close();
});

async function openPlayer(query) {
  const page = await openPage(chromium.browser, `${chromium.base}/web/player/?${query}`);
  await page.waitForFunction(() => window.m4dPlayer && window.m4dPlayer.state.frame, { timeout: 30000 });
  assert.deepEqual(page.problems, []);
  return page;
}

// PSNR in dB of the player's canvas against a PNG (bytes).
const psnrAgainstPng = (page, png) => psnrOf(page, png, 'm4dPlayer');

test('draws a frame as the native renderer does (PSNR >= 40 dB)', async (t) => {
  const stream = 'conformance/streams/enc_adaptive_gop.m4d';
  const dir = mkdtempSync(join(tmpdir(), 'm4d-player-'));
  try {
    // The orbit camera at angle 0, which the page's orbit starts at.
    execFileSync(join(root, 'build/release/tools/m4d_play'), [
      join(root, stream), '--orbit', '--orbit-degrees', '0', '--width', '320', '--height', '240',
      '--frames', '5', '-o', dir]);
    const page = await openPlayer(`stream=/${stream}&width=320&height=240&autoplay=0`);
    for (const frame of [4, 0]) {  // an inter frame, then a keyframe (seeking back)
      assert.equal(await page.evaluate((f) => window.m4dPlayer.showFrame(f), frame), frame);
      const png = readFileSync(join(dir, `frame_0000${frame}.png`));
      const psnr = await psnrAgainstPng(page, png);
      t.diagnostic(`frame ${frame}: ${psnr.toFixed(2)} dB against m4d_play`);
      assert.ok(psnr >= 40, `frame ${frame}: ${psnr.toFixed(2)} dB against m4d_play`);
    }
    // Foreground only draws less than both layers.
    const both = await page.evaluate(() => window.m4dPlayer.readRgb().reduce((a, b) => a + b, 0));
    await page.click('#foreground');
    await page.evaluate(() => window.m4dPlayer.showFrame(0));
    const foreground = await page.evaluate(() => window.m4dPlayer.readRgb().reduce((a, b) => a + b, 0));
    assert.ok(foreground < both, `foreground ${foreground} against ${both}`);
    await page.close();
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test('draws a capture camera and a replaced background as m4d_play does', async (t) => {
  const stream = join(root, 'conformance/streams/enc_adaptive_gop.m4d');
  const background = join(root, 'conformance/streams/enc_sh3.m4d');
  const dir = mkdtempSync(join(tmpdir(), 'm4d-player-'));
  const capture = join(dir, 'scene');
  const files = await serve(dir);
  try {
    // The conformance streams' scene (scripts/make_conformance.sh): its transforms.json.
    execFileSync(join(root, 'build/release/tools/m4d/m4d'), ['scene', '-o', capture, '--cameras', '6',
      '--width', '64', '--height', '48', '--frames', '6', '--points', '2000']);
    const play = (out, ...extra) => execFileSync(join(root, 'build/release/tools/m4d_play'), [stream,
      '--capture', capture, '--camera', '1', '--width', '320', '--height', '240', '--frames', '1',
      '-o', out, ...extra]);
    play(dir);
    const replaced = join(dir, 'replaced');
    mkdirSync(replaced);
    play(replaced, '--background-stream', background);
    const cameras = `http://127.0.0.1:${files.address().port}/scene/transforms.json`;
    const page = await openPlayer(`stream=/conformance/streams/enc_adaptive_gop.m4d&width=320&height=240` +
      `&autoplay=0&cameras=${encodeURIComponent(cameras)}&camera=1&background=/conformance/streams/enc_sh3.m4d`);
    await page.waitForFunction(() => window.m4dPlayer.state.cameras.length === 6 &&
      !document.getElementById('replace-background').disabled, { timeout: 30000 });
    await page.evaluate(() => window.m4dPlayer.showFrame(0));
    const own = await psnrAgainstPng(page, readFileSync(join(dir, 'frame_00000.png')));
    t.diagnostic(`capture camera 1: ${own.toFixed(2)} dB against m4d_play`);
    assert.ok(own >= 40, `capture camera: ${own.toFixed(2)} dB`);
    // The replacement applies from the next frame on: switch it on, then show frame 0 again.
    await page.click('#replace-background');
    await page.evaluate(() => window.m4dPlayer.showFrame(0));
    const swapped = await psnrAgainstPng(page, readFileSync(join(replaced, 'frame_00000.png')));
    t.diagnostic(`replaced background: ${swapped.toFixed(2)} dB against m4d_play --background-stream`);
    assert.ok(swapped >= 40, `replaced background: ${swapped.toFixed(2)} dB`);
    const unchanged = await psnrAgainstPng(page, readFileSync(join(dir, 'frame_00000.png')));
    assert.ok(unchanged < 30, `the background did not change (${unchanged.toFixed(2)} dB)`);
    await page.close();
  } finally {
    files.close();
    rmSync(dir, { recursive: true, force: true });
  }
});

test('the play button and the seek bar drive playback', async () => {
  const page = await openPlayer('stream=/conformance/streams/synth_sh3_three_gops.m4d&width=160&height=120&autoplay=0');
  await page.evaluate(() => window.m4dPlayer.loaded);
  assert.equal(await page.$eval('#play', (b) => b.textContent), 'Play');
  assert.equal(await page.$eval('#seek', (e) => e.max), '11');
  // The seek bar: frame 9 shows, in the third GOP.
  await page.$eval('#seek', (e) => { e.value = '9'; e.dispatchEvent(new Event('input')); });
  await page.waitForFunction(() => window.m4dPlayer.state.frame.index === 9, { timeout: 30000 });
  assert.match(await page.$eval('#frame', (e) => e.textContent), /^frame 9 \/ 11/);
  // Play: frames advance past 9; pause: they stop.
  await page.click('#play');
  await page.waitForFunction(() => window.m4dPlayer.state.frame.index !== 9, { timeout: 30000 });
  await page.click('#play');
  assert.equal(await page.$eval('#play', (b) => b.textContent), 'Play');
  const paused = await page.evaluate(() => window.m4dPlayer.state.frame.index);
  await new Promise((done) => setTimeout(done, 500));
  assert.equal(await page.evaluate(() => window.m4dPlayer.state.frame.index), paused);
  await page.close();
});

test('a damaged stream shows an error and resumes at the next GOP', async () => {
  // entropy_rans_damaged: frame 1's motion grid is damaged; frames 0 and 3-5 decode.
  const page = await openPlayer('stream=/conformance/invalid/entropy_rans_damaged.m4d&width=160&height=120');
  await page.waitForFunction(() => window.m4dPlayer.state.lastShown === 5, { timeout: 30000 });
  const error = await page.$eval('#error', (e) => e.textContent);
  assert.match(error, /M4D_ERR_BITSTREAM/);
  assert.match(error, /resumes at the next GOP/);
  await page.close();
});

test('streams progressively: playback starts before the last byte arrives', async () => {
  // A server that sends the first half of the stream, then holds the rest back.
  const data = readFileSync(join(root, 'conformance/streams/synth_sh3_three_gops.m4d'));
  let finish;
  const slow = createServer((request, response) => {
    response.writeHead(200, { 'Content-Type': 'application/octet-stream', 'Access-Control-Allow-Origin': '*' });
    response.write(data.subarray(0, data.length >> 1));
    finish = () => response.end(data.subarray(data.length >> 1));
  });
  await new Promise((done) => slow.listen(0, '127.0.0.1', done));
  const url = `http://127.0.0.1:${slow.address().port}/slow.m4d`;
  const page = await openPlayer(`stream=${encodeURIComponent(url)}&width=160&height=120`);
  try {
    assert.equal(await page.evaluate(() => window.m4dPlayer.state.ended), false);
    finish();
    await page.waitForFunction(() => window.m4dPlayer.state.ended && window.m4dPlayer.state.lastShown === 11, { timeout: 30000 });
    assert.equal(await page.$eval('#error', (e) => e.textContent), '');
  } finally {
    await page.close();
    slow.close();
  }
});
