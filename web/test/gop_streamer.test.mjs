// Streaming by GOP over HTTP (web/js/gop_streamer.mjs) against the local server
// (web/tools/serve.mjs), which records every range it serves: the first frame decodes after
// only the first GOP's bytes were served, a seek serves nothing before its random-access GOP,
// no byte is served twice, and the frames decode with the hashes of the whole file. The GOP
// index sidecars come from m4d_probe --gop-index (needs scripts/build.sh m4d_probe and
// scripts/build_web.sh).
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { copyFileSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { createServer } from 'node:http';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { fileURLToPath } from 'node:url';

import { GopStreamer, checkGopIndex } from '../js/gop_streamer.mjs';
import { parseRange, serve } from '../tools/serve.mjs';

const root = fileURLToPath(new URL('../../', import.meta.url));
const moduleDir = process.env.M4D_WEB_MODULE_DIR
  ? new URL(`file://${process.env.M4D_WEB_MODULE_DIR.replace(/\/?$/, '/')}`)
  : new URL('build/web/module/', `file://${root}`);
const { loadM4d } = await import(new URL('m4d.mjs', moduleDir));
const m4d = await loadM4d();

const streams = join(root, 'conformance/streams');
// The whole file's frame hashes, "index hash" per frame.
const expected = (name) => readFileSync(join(streams, `${name}.md5`), 'utf8').split('\n').filter(Boolean);

let dir;
let server;
let base;
const served = [];  // every request the server answered: { method, path, status, range, bytes }

before(async () => {
  dir = mkdtempSync(join(tmpdir(), 'm4d-gops-'));
  for (const name of ['synth_sh3_three_gops', 'synth_sh1_dependent_gops', 'enc_adaptive_gop', 'edit_frame_index_wraps']) {
    copyFileSync(join(streams, `${name}.m4d`), join(dir, `${name}.m4d`));
    execFileSync(join(root, 'build/release/tools/m4d_probe'),
      ['--gop-index', join(dir, `${name}.m4d`), '-o', join(dir, `${name}.m4d.gops.json`)]);
  }
  server = await serve(dir, 0, { onRequest: (log) => served.push(log) });
  base = `http://127.0.0.1:${server.address().port}`;
});

after(() => {
  server?.close();
  if (dir) rmSync(dir, { recursive: true, force: true });
});

// The ranges served of `path` from request `from` on.
const rangesOf = (path, from = 0) => served.slice(from).filter((r) => r.path === path).map((r) => r.range);

// No byte of `path` served twice, and never the whole file.
function assertServedOnce(path) {
  const ranges = rangesOf(path);
  assert.ok(ranges.every((r) => r !== null), 'every request of the stream is a range request');
  const sorted = [...ranges].sort((a, b) => a[0] - b[0]);
  for (let i = 1; i < sorted.length; ++i) {
    assert.ok(sorted[i][0] > sorted[i - 1][1], `ranges ${sorted[i - 1]} and ${sorted[i]} overlap`);
  }
}

test('the first frame decodes from the first GOP alone; a seek serves from its random-access GOP on', async () => {
  const name = 'synth_sh3_three_gops';
  const path = `/${name}.m4d`;
  const hashes = expected(name);
  const from = served.length;
  // No read-ahead: every range served is one playback needed.
  const streamer = await GopStreamer.open({ m4d, url: `${base}${path}`, readAhead: 0 });
  const { gops } = streamer.index;
  assert.ok(gops.length >= 3 && gops[2].random_access);
  assert.deepEqual(rangesOf(path, from), [], 'nothing of the stream before the first nextFrame');

  const first = await streamer.nextFrame();
  assert.equal(`${first.frameIndex} ${first.hash()}`, hashes[0]);
  assert.deepEqual(rangesOf(path, from), [[0, gops[0].bytes - 1]], 'only the first GOP was served');
  // The frame came out before the whole GOP was pushed: its keyframe and the next frame.
  assert.ok(streamer.decoder.bufferedBytes <= gops[0].bytes);

  const second = await streamer.nextFrame();
  assert.equal(`${second.frameIndex} ${second.hash()}`, hashes[1]);

  const seekFrom = served.length;
  streamer.seek(10);
  const target = await streamer.nextFrame();
  assert.equal(`${target.frameIndex} ${target.hash()}`, hashes[10], 'the same hash as the whole file');
  // Only the random-access GOP of frame 10: nothing of GOP 1, which the seek skips.
  assert.deepEqual(rangesOf(path, seekFrom), [[gops[2].offset, gops[2].offset + gops[2].bytes - 1]]);
  const last = await streamer.nextFrame();
  assert.equal(`${last.frameIndex} ${last.hash()}`, hashes[11]);
  assert.equal(await streamer.nextFrame(), null);
  assertServedOnce(path);
  streamer.close();
});

test('the first frame comes out while the rest of its GOP is still on its way', async () => {
  // A server that sends the first GOP's keyframe, then holds the rest of the range until the
  // test has decoded the first frame: a streamer that waited for the whole GOP would hang.
  const name = 'synth_sh3_three_gops';
  const stream = readFileSync(join(dir, `${name}.m4d`));
  const index = readFileSync(join(dir, `${name}.m4d.gops.json`));
  const probe = JSON.parse(execFileSync(join(root, 'build/release/tools/m4d_probe'), ['--json', join(dir, `${name}.m4d`)]));
  const keyframe = probe.frames[0].packets.at(-1);
  const keyframeEnd = keyframe.offset + keyframe.bytes;
  let release;
  const released = new Promise((done) => { release = done; });
  const held = createServer(async (request, response) => {
    if (request.url.endsWith('.json')) {
      response.writeHead(200).end(index);
      return;
    }
    const [start, end] = parseRange(request.headers.range, stream.length);
    response.writeHead(206, { 'Content-Range': `bytes ${start}-${end}/${stream.length}`, 'Content-Length': end - start + 1 });
    response.write(stream.subarray(start, Math.min(end + 1, keyframeEnd)));
    await released;
    response.end(stream.subarray(Math.min(end + 1, keyframeEnd), end + 1));
  });
  await new Promise((done) => held.listen(0, '127.0.0.1', done));
  try {
    const streamer = await GopStreamer.open({ m4d, url: `http://127.0.0.1:${held.address().port}/${name}.m4d`, readAhead: 0 });
    assert.ok(keyframeEnd < streamer.index.gops[0].bytes);
    const first = await streamer.nextFrame();
    assert.equal(`${first.frameIndex} ${first.hash()}`, expected(name)[0]);
    assert.equal(streamer.decoder.bufferedBytes, keyframeEnd, 'decoded from the keyframe bytes alone');
    release();
    const second = await streamer.nextFrame();
    assert.equal(`${second.frameIndex} ${second.hash()}`, expected(name)[1]);
    streamer.close();
  } finally {
    release();
    held.close();
  }
});

test('a seek into a dependent GOP fetches from its random-access GOP and nothing twice', async () => {
  const name = 'synth_sh1_dependent_gops';
  const path = `/${name}.m4d`;
  const hashes = expected(name);
  const streamer = await GopStreamer.open({ m4d, url: `${base}${path}`, readAhead: 0 });
  const { gops } = streamer.index;
  const target = gops[2].frame + 1;
  assert.equal(gops[2].random_access, false);
  assert.equal(streamer.randomAccessGopOf(target), 0);
  streamer.seek(target);
  const frame = await streamer.nextFrame();
  assert.equal(`${frame.frameIndex} ${frame.hash()}`, hashes[target]);
  assert.deepEqual(rangesOf(path), gops.map((g) => [g.offset, g.offset + g.bytes - 1]));
  // Back into the first GOP: its bytes are kept, nothing is requested again.
  const before = served.length;
  streamer.seek(1);
  const again = await streamer.nextFrame();
  assert.equal(`${again.frameIndex} ${again.hash()}`, hashes[1]);
  assert.equal(served.length, before);
  assertServedOnce(path);
  assert.throws(() => streamer.seek(streamer.frames), RangeError);
  streamer.close();
});

test('plays a whole stream with the whole file hashes', async () => {
  const name = 'enc_adaptive_gop';
  const streamer = await GopStreamer.open({ m4d, url: `${base}/${name}.m4d` });
  const lines = [];
  const first = await streamer.nextFrame();
  lines.push(`${first.frameIndex} ${first.hash()}`);
  // Read-ahead (1 GOP): the next GOP is requested once a frame of the first came out.
  assert.deepEqual(streamer.requests.map((r) => r.gop), [0, 1]);
  for (let f; (f = await streamer.nextFrame()); ) lines.push(`${f.frameIndex} ${f.hash()}`);
  assert.deepEqual(lines, expected(name));
  assert.equal(streamer.decoder.errors.count, 0);
  assertServedOnce(`/${name}.m4d`);
  streamer.close();
});

test('frame numbers that wrap at 2^32 inside a GOP', async () => {
  const name = 'edit_frame_index_wraps';
  const hashes = expected(name);
  const streamer = await GopStreamer.open({ m4d, url: `${base}/${name}.m4d` });
  const { gops } = streamer.index;
  assert.ok(gops[0].frame + gops[0].frames > 2 ** 32, 'the first GOP holds the wrap');
  assert.equal(streamer.gopOf(0), 0);
  const lines = [];
  for (let f; (f = await streamer.nextFrame()); ) lines.push(`${f.frameIndex} ${f.hash()}`);
  assert.deepEqual(lines, hashes);
  streamer.seek(0);  // frame 0, after 2^32 - 1, in the first GOP
  const frame = await streamer.nextFrame();
  assert.equal(`${frame.frameIndex} ${frame.hash()}`, hashes[2]);
  assertServedOnce(`/${name}.m4d`);
  streamer.close();
});

test('clear errors: 404, an index of another stream, a server without ranges', async () => {
  await assert.rejects(GopStreamer.open({ m4d, url: `${base}/missing.m4d` }), /GOP index .*HTTP 404/);
  // The index exists, the stream does not.
  copyFileSync(join(dir, 'enc_adaptive_gop.m4d.gops.json'), join(dir, 'gone.m4d.gops.json'));
  const gone = await GopStreamer.open({ m4d, url: `${base}/gone.m4d` });
  await assert.rejects(gone.nextFrame(), /gone\.m4d: HTTP 404/);
  gone.close();
  // The index of another stream: its sizes do not match.
  const wrong = await GopStreamer.open({
    m4d, url: `${base}/synth_sh3_three_gops.m4d`, indexUrl: `${base}/enc_adaptive_gop.m4d.gops.json`,
  });
  await assert.rejects(wrong.nextFrame(), /index does not match the stream/);
  wrong.close();
  // Not an index.
  writeFileSync(join(dir, 'bad.m4d.gops.json'), JSON.stringify({ format: 'm4d-gop-index', version: 1, gops: [] }));
  await assert.rejects(GopStreamer.open({ m4d, url: `${base}/bad.m4d` }), /lists no GOP/);
  assert.throws(() => checkGopIndex({ format: 'x' }), /is not an m4d-gop-index/);

  // Closed while a frame is awaited from a server that sends nothing: the wait rejects.
  const silentIndex = readFileSync(join(dir, 'enc_adaptive_gop.m4d.gops.json'));
  const silent = createServer((request, response) => {
    if (request.url.endsWith('.json')) response.writeHead(200).end(silentIndex);
    else response.writeHead(206, { 'Content-Range': request.headers.range.replace('=', ' ') + '/' + JSON.parse(silentIndex).stream_bytes });
  });
  await new Promise((done) => silent.listen(0, '127.0.0.1', done));
  try {
    const streamer = await GopStreamer.open({ m4d, url: `http://127.0.0.1:${silent.address().port}/s.m4d` });
    const pending = streamer.nextFrame();
    streamer.close();
    await assert.rejects(pending, /closed/);
  } finally {
    silent.closeAllConnections();
    silent.close();
  }

  // A server that answers every request with the whole file.
  const index = readFileSync(join(dir, 'enc_adaptive_gop.m4d.gops.json'));
  const stream = readFileSync(join(dir, 'enc_adaptive_gop.m4d'));
  const plain = createServer((request, response) => {
    response.writeHead(200).end(request.url.endsWith('.json') ? index : stream);
  });
  await new Promise((done) => plain.listen(0, '127.0.0.1', done));
  try {
    const streamer = await GopStreamer.open({ m4d, url: `http://127.0.0.1:${plain.address().port}/s.m4d` });
    await assert.rejects(streamer.nextFrame(), /ignores range requests/);
    streamer.close();
  } finally {
    plain.close();
  }
});

test('the server answers ranges with 206, bad ones with 416', async () => {
  assert.deepEqual(parseRange(undefined, 10), null);
  assert.deepEqual(parseRange('bytes=2-4', 10), [2, 4]);
  assert.deepEqual(parseRange('bytes=8-', 10), [8, 9]);
  assert.deepEqual(parseRange('bytes=-3', 10), [7, 9]);
  assert.deepEqual(parseRange('bytes=5-100', 10), [5, 9]);
  for (const bad of ['bytes=10-', 'bytes=4-2', 'bytes=-0', 'bytes=-', 'items=1-2', 'bytes=1-2,4-5']) {
    assert.equal(parseRange(bad, 10), 'invalid', bad);
  }
  const url = `${base}/enc_adaptive_gop.m4d`;
  const whole = readFileSync(join(dir, 'enc_adaptive_gop.m4d'));
  const part = await fetch(url, { headers: { Range: 'bytes=100-199' } });
  assert.equal(part.status, 206);
  assert.equal(part.headers.get('content-range'), `bytes 100-199/${whole.length}`);
  assert.equal(part.headers.get('accept-ranges'), 'bytes');
  assert.deepEqual(new Uint8Array(await part.arrayBuffer()), new Uint8Array(whole.subarray(100, 200)));
  const beyond = await fetch(url, { headers: { Range: `bytes=${whole.length}-` } });
  assert.equal(beyond.status, 416);
  assert.equal(beyond.headers.get('content-range'), `bytes */${whole.length}`);
  await beyond.arrayBuffer();
  const full = await fetch(url);
  assert.equal(full.status, 200);
  assert.equal((await full.arrayBuffer()).byteLength, whole.length);
});
