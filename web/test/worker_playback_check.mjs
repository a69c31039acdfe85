// A check both viewer example tests (Spark, PlayCanvas) make of their page: it decodes in a
// Web Worker (M4dWorkerDecoder) paced by PlayerCore, shows frames in order (dropping some if
// decoding fell behind) and loops; the main thread loads no wasm. A helper with no tests.
import assert from 'node:assert/strict';

/**
 * Waits until the example page (its test object window[global]) has looped on a 6-frame
 * stream at 30 fps, then asserts the above of what it showed.
 */
export async function checkWorkerPlayback(page, global) {
  await page.waitForFunction((name) => {
    const h = window[name].state.history;
    return h.some((f, i) => i > 0 && f < h[i - 1]) && h.at(-1) >= 2;
  }, { timeout: 15000 }, global);
  const seen = await page.evaluate((name) => {
    const { decoder, core, state } = window[name];
    return {
      worker: decoder.constructor.name, fps: decoder.streamInfo().fps, playing: core.playing,
      stats: { ...core.stats }, history: state.history.slice(),
      wasmOnPage: performance.getEntriesByType('resource').filter((e) => /m4d_wasm|m4d\.mjs/.test(e.name)).map((e) => e.name),
    };
  }, global);
  assert.equal(seen.worker, 'M4dWorkerDecoder');
  assert.equal(seen.fps, 30);
  assert.equal(seen.playing, true);
  assert.deepEqual(seen.wasmOnPage, [], 'the decoder is loaded by the worker only');
  const h = seen.history;
  assert.ok(h.every((f) => Number.isInteger(f) && f >= 0 && f < 6), h.join(' '));
  for (let i = 1; i < h.length; ++i) {
    assert.ok(h[i] > h[i - 1] || h[i] === 0, `frame ${h[i]} after ${h[i - 1]}: ${h.join(' ')}`);
  }
  assert.ok(seen.stats.shown >= h.length);
}
