// Adaptive bitrate in the viewers: the Spark and PlayCanvas example pages (web/examples/) with
// ?manifest=URL play the renditions of abr_fixture.mjs (r1, r5) in headless Chromium
// (puppeteer-core, SwiftShader) from the throttled local server (web/tools/throttled_server.mjs),
// whose rate the test sets per GOP request: fast (10x the top rendition's bandwidth), then
// slow (the top rendition's bandwidth, far below what it needs with the safety factor), then
// fast again. Each page steps up, down and up at random-access GOPs, the first frame shown of
// each new rendition carries its static layer, frame indices only increase across switches,
// and no GOP arrives (nor frame shows) more than a GOP's duration late. Needs scripts/build.sh and
// scripts/build_web.sh.
import assert from 'node:assert/strict';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { throttledServer } from '../tools/throttled_server.mjs';
import { encodeRenditions } from './abr_fixture.mjs';
import { openPage, startChromium } from './chromium_harness.mjs';

let chromium, dir, manifest;

before(async () => {
  dir = mkdtempSync(join(tmpdir(), 'm4d-abr-viewer-'));
  manifest = encodeRenditions(dir);
  chromium = await startChromium();
});

after(async () => {
  await chromium?.close();
  if (dir) rmSync(dir, { recursive: true, force: true });
});

// Plays the manifest in an example page ('spark' or 'playcanvas', whose test object is
// window[global]) with the rate following the GOP requests; returns what the page logged.
async function playThrottled(example, global) {
  const renditions = await throttledServer(dir);
  const high = manifest.renditions[manifest.renditions.length - 1];
  const slow = high.bandwidth / 8, fast = 10 * slow;
  // GOP requests 3 to 5 (0-based) are served slowly, the others fast.
  const requestMs = [];
  Object.defineProperty(renditions, 'rate', {
    get() {
      const g = renditions.served.filter((s) => s.url.endsWith('.m4d')).length - 1;
      requestMs[g] = performance.now();
      return g >= 3 && g < 6 ? slow : fast;
    },
  });
  let page;
  try {
    page = await openPage(chromium.browser, `${chromium.base}/web/examples/${example}/?manifest=` +
      `${encodeURIComponent(`${renditions.base}abr.manifest.json`)}&width=160&height=120&mesh=0`);
    const last = manifest.frames - 1;
    await page.waitForFunction((name, lastFrame) => {
      const abr = window[name] && window[name].abr;
      return abr && abr.shown.length && abr.shown[abr.shown.length - 1].index === lastFrame;
    }, { timeout: 20000, polling: 50 }, global, last);
    const log = await page.evaluate((name) => {
      const { abr } = window[name];
      return { shown: abr.shown, switchLog: abr.switchLog, stalls: abr.stalls,
        readout: document.getElementById('readout').textContent, error: document.getElementById('error').textContent };
    }, global);
    assert.deepEqual(page.problems, []);
    assert.equal(log.error, '');
    return { ...log, requestMs, requests: renditions.served.filter((s) => s.url.endsWith('.m4d')).map((s) => s.url) };
  } finally {
    await page?.close();
    await renditions.close();
  }
}

function checkPlayback(log) {
  const gopMs = (1000 * manifest.renditions[0].gops[0].frames) / manifest.fps;
  // Up at the start (once the first fetches, slowed by connection set-up and CORS preflights,
  // are measured: not always at the first GOP), down after the slow GOPs began, up after they
  // ended; all at random-access GOPs.
  const switches = log.switchLog.map(({ frame, from, to }) => `${frame} ${from}>${to}`);
  assert.ok(switches.length === 3 && /^[246] r1>r5$/.test(switches[0]), JSON.stringify(log.switchLog));
  assert.deepEqual(switches.slice(1), ['8 r5>r1', '14 r1>r5'], JSON.stringify(log.switchLog));
  const gopStarts = new Set(manifest.renditions[0].gops.filter((g) => g.random_access).map((g) => g.frame));
  for (const s of log.switchLog) assert.ok(gopStarts.has(s.frame), `switch at frame ${s.frame}`);
  // Each GOP fetched once, from the rendition the switches say.
  const expected = manifest.renditions[0].gops.map((g) => {
    const before = log.switchLog.filter((s) => s.frame <= g.frame);
    return `/abr.${before.length ? before[before.length - 1].to : 'r1'}.m4d`;
  });
  assert.deepEqual(log.requests, expected);
  // Frames kept coming: indices increase, from the first to the last.
  const indices = log.shown.map((f) => f.index);
  assert.equal(indices[0], 0);
  for (let i = 1; i < indices.length; ++i) assert.ok(indices[i] > indices[i - 1], JSON.stringify(indices));
  // Each rendition's first frame shown has its static layer, and comes from that rendition.
  for (const s of log.switchLog) {
    const first = log.shown.find((f) => f.index >= s.frame);
    assert.equal(first.rendition, s.to, JSON.stringify(first));
    assert.equal(first.staticChanged, true, JSON.stringify(first));
  }
  assert.equal(log.shown[0].staticChanged, true);
  // No GOP arrived more than a GOP's duration after its frames were due.
  for (const s of log.stalls.list) assert.ok(s.ms < gopMs, JSON.stringify(log.stalls));
  // Nor did the page wait longer than a GOP beyond a frame's duration between frames shown.
  const frameMs = 1000 / manifest.fps;
  for (let i = 1; i < log.shown.length; ++i) {
    const late = log.shown[i].ms - log.shown[i - 1].ms - (indices[i] - indices[i - 1]) * frameMs;
    assert.ok(late < gopMs, `frame ${indices[i]} shown ${late.toFixed(0)} ms late`);
  }
  assert.match(log.readout, /rendition r5/);
}

test('the Spark page steps down and back up under throttling, frames keep coming', async () => {
  const log = await playThrottled('spark', 'm4dSpark');
  checkPlayback(log);
  if (process.env.M4D_ABR_REPORT) console.log(JSON.stringify({ spark: log }));
});

test('the PlayCanvas page steps down and back up under throttling, frames keep coming', async () => {
  const log = await playThrottled('playcanvas', 'm4dPlayCanvas');
  checkPlayback(log);
  if (process.env.M4D_ABR_REPORT) console.log(JSON.stringify({ playcanvas: log }));
});
