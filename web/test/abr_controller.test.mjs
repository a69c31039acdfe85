// Adaptive bitrate (web/js/abr_controller.mjs) against a throttled local HTTP server: two
// renditions of a tiny generated scene made by `m4d encode --renditions r1,r5` (abr_fixture.mjs;
// needs the native build, scripts/build.sh), served with Range support at a rate the test sets per GOP.
// The rates are 10x apart, far from the decision thresholds, so the decisions do not depend
// on timing: the controller steps up at the start, down when the rate falls, up when it
// recovers, never stalls longer than a GOP, and every frame decodes to the hash of its own
// rendition's frame. Run: node --test web/test/ (after scripts/build_web.sh).
import assert from 'node:assert/strict';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { test } from 'node:test';

import { AbrController, chooseRendition, validateManifest } from '../js/abr_controller.mjs';
import { throttledServer } from '../tools/throttled_server.mjs';
import { encodeRenditions } from './abr_fixture.mjs';

const root = new URL('../../', import.meta.url);
const moduleDir = process.env.M4D_WEB_MODULE_DIR
  ? new URL(`file://${process.env.M4D_WEB_MODULE_DIR.replace(/\/?$/, '/')}`)
  : new URL('build/web/module/', root);
const { loadM4d } = await import(new URL('m4d.mjs', moduleDir));
const m4d = await loadM4d();

// Frame index -> hash of a whole stream decoded at once.
function referenceHashes(path) {
  const decoder = m4d.openDecoder();
  decoder.push(readFileSync(path));
  decoder.end();
  const hashes = new Map();
  for (let f; (f = decoder.nextFrame()); ) hashes.set(f.frameIndex, f.hash());
  decoder.close();
  return hashes;
}

test('chooses down with a safety factor, up with a margin', () => {
  const r = [{ bandwidth: 100 }, { bandwidth: 200 }, { bandwidth: 400 }];
  assert.equal(chooseRendition(r, 2, 400), 1);  // 400 > 0.75 * 400: down to 200 <= 300
  assert.equal(chooseRendition(r, 2, 600), 2);
  assert.equal(chooseRendition(r, 1, 100), 0);  // nothing fits: the lowest
  assert.equal(chooseRendition(r, 0, 500), 1);  // 400 * 1.5 > 500; 200 * 1.5 <= 500
  assert.equal(chooseRendition(r, 1, 280), 1);  // between down (267) and up (300): stays
  assert.throws(() => validateManifest({ format: 'm4d-gop-index' }), /m4d manifest: format/);
});

test('steps down when throughput falls and up when it recovers, without a long stall', async () => {
  const dir = mkdtempSync(join(tmpdir(), 'm4d-abr-'));
  let server;
  try {
    const manifest = encodeRenditions(dir);
    assert.deepEqual(manifest.renditions.map((r) => r.id), ['r1', 'r5']);
    const [low, high] = manifest.renditions;
    assert.ok(low.bytes < high.bytes);
    const gops = low.gops.length;
    assert.equal(gops, 8);
    const reference = { r1: referenceHashes(join(dir, 'abr.r1.m4d')),
      r5: referenceHashes(join(dir, 'abr.r5.m4d')) };
    assert.notDeepEqual([...reference.r1.values()], [...reference.r5.values()]);

    // Rates in bytes per second: "slow" is the high rendition's bandwidth (25% above what
    // the high rendition may use, and above the low one's), "fast" 10 times that. At 5 fps
    // a fast GOP fetch takes about 30 ms, so that a request's own latency on a busy machine
    // (10-50 ms) leaves the measured throughput well above the step-up threshold.
    server = await throttledServer(dir);
    const slow = high.bandwidth / 8, fast = 10 * slow;
    const rateOf = (g) => (g >= 3 && g < 6 ? slow : fast);
    const gopSeconds = 2 / manifest.fps;
    const decoded = [];
    const abr = new AbrController({
      manifestUrl: `${server.base}abr.manifest.json`,
      openDecoder: () => m4d.openDecoder(),
      onFrame: (f, id) => decoded.push({ frame: f.frameIndex, id, hash: f.hash() }),
      maxBufferSeconds: 3 * gopSeconds,
    });
    await abr.load();
    assert.equal(abr.rendition, 'r1');
    const results = [];
    for (let g = 0; g < gops; ++g) {
      server.rate = rateOf(g);
      results.push(await abr.nextGop());
    }
    assert.equal(await abr.nextGop(), null);
    abr.close();

    // Up at once (fast from the start), down after the first slow GOP, up after the first
    // fast one again: each a GOP after the rate changed.
    const log = abr.switchLog.map(({ frame, from, to }) => `${frame} ${from}>${to}`);
    assert.deepEqual(log, ['2 r1>r5', '8 r5>r1', '14 r1>r5'], JSON.stringify(abr.switchLog));
    assert.deepEqual(results.map((r) => r.rendition),
      ['r1', 'r5', 'r5', 'r5', 'r1', 'r1', 'r1', 'r5']);
    for (const s of abr.switchLog) {
      if (s.to === 'r1') assert.ok(s.throughput <= high.bandwidth * 1.01, JSON.stringify(s));
    }
    // No stall beyond one GOP's duration.
    for (const s of abr.stalls.list) assert.ok(s.ms < gopSeconds * 1000, JSON.stringify(s));
    // Every frame once, in order, each with its own rendition's hash.
    assert.deepEqual(decoded.map((d) => d.frame), [...Array(manifest.frames).keys()]);
    for (const d of decoded) assert.equal(d.hash, reference[d.id].get(d.frame), `frame ${d.frame}`);
    // Only the GOPs played were fetched, each by one Range request of its own rendition.
    const fetched = server.served.filter((s) => s.url.endsWith('.m4d'));
    assert.equal(fetched.length, gops);
    fetched.forEach((s, g) => {
      const gop = manifest.renditions.find((r) => r.id === results[g].rendition).gops[g];
      assert.equal(s.url, `/abr.${results[g].rendition}.m4d`);
      assert.deepEqual([s.first, s.last], [gop.offset, gop.offset + gop.bytes - 1]);
    });
    if (process.env.M4D_ABR_REPORT) {
      console.log(JSON.stringify({ manifest: manifest.renditions.map(({ gops: _, ...r }) => r),
        results, switchLog: abr.switchLog, stalls: abr.stalls, slow, fast }, null, 1));
    }
  } finally {
    if (server) await server.close();
    rmSync(dir, { recursive: true, force: true });
  }
});
