// Tests of the WebAssembly decoder's JavaScript API (web/js/m4d.mjs) on the conformance
// streams. Run: node --test web/test/ (after scripts/build_web.sh).
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, readdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { test } from 'node:test';
import { fileURLToPath } from 'node:url';

const root = new URL('../../', import.meta.url);
const moduleDir = process.env.M4D_WEB_MODULE_DIR
  ? new URL(`file://${process.env.M4D_WEB_MODULE_DIR.replace(/\/?$/, '/')}`)
  : new URL('build/web/module/', root);
const { loadM4d } = await import(new URL('m4d.mjs', moduleDir));
// The versions the public C header declares (M4D_VERSION_*, M4D_BITSTREAM_VERSION_*).
const header = readFileSync(new URL('sdk/include/m4d/m4d.h', root), 'utf8');
const define = (name) => header.match(new RegExp(`#define ${name} (\\d+)`))[1];
const m4d = await loadM4d();

const streams = new URL('conformance/streams/', root);
const invalid = new URL('conformance/invalid/', root);
const read = (dir, name) => readFileSync(new URL(name, dir));
const expectedLines = (dir, name) => read(dir, name).toString().split('\n').filter(Boolean);

// Decodes `data` pushed in chunks of `chunk` bytes; returns the hash lines and the decoder
// (ended, not closed).
function decodeAll(data, { chunk = data.length, layers = 'all' } = {}) {
  const decoder = m4d.openDecoder({ layers });
  const lines = [];
  const drain = () => {
    for (let f; (f = decoder.nextFrame()); ) lines.push(`${f.frameIndex} ${f.hash()}`);
  };
  for (let at = 0; at < data.length; at += chunk) {
    decoder.push(data.subarray(at, at + chunk));
    drain();
  }
  decoder.end();
  drain();
  return { lines, decoder };
}

test('decodes bit-exactly whatever the chunk size', () => {
  const data = read(streams, 'enc_adaptive_gop.m4d');
  const expected = expectedLines(streams, 'enc_adaptive_gop.md5');
  for (const chunk of [1, 23, 4096, data.length]) {
    const { lines, decoder } = decodeAll(data, { chunk });
    assert.deepEqual(lines, expected, `chunks of ${chunk} bytes`);
    assert.equal(decoder.errors.count, 0);
    assert.equal(decoder.bufferedBytes, data.length);
    decoder.close();
  }
});

test('outputs one layer when asked', () => {
  const data = read(streams, 'synth_sh3_three_gops.m4d');
  for (const layers of ['static', 'dynamic']) {
    const { lines, decoder } = decodeAll(data, { layers });
    assert.deepEqual(lines, expectedLines(streams, `synth_sh3_three_gops.${layers}.md5`));
    decoder.close();
  }
  assert.throws(() => m4d.openDecoder({ layers: 'both' }), RangeError);
});

// The motion kernel has code of its own for each channel count of a grid level (1 to 8), and
// the WebAssembly build spells its gathers with SIMD128; the conformance streams hold 1, 2, 4
// and 8 channels. Needs the native build (m4d_synth, m4d_decode).
test('decodes every grid channel count as the native decoder does', () => {
  const tools = fileURLToPath(new URL('build/release/tools/', root));
  const dir = mkdtempSync(join(tmpdir(), 'm4d-channels-'));
  try {
    for (const grid of ['8,3,16,5,12,6,8,7', '16,1,8,2,8,4,16,8']) {
      const stream = join(dir, 'grid.m4d');
      execFileSync(join(tools, 'm4d_synth'), ['-o', stream, '--force', '--gops', '1', '--frames-per-gop', '3',
        '--static', '50', '--dynamic', '3000', '--grid', grid, '--motion-fraction', '0.5']);
      const expected = execFileSync(join(tools, 'm4d_decode'), [stream], { stdio: ['ignore', 'pipe', 'ignore'] })
        .toString().split('\n').filter(Boolean);
      const { lines, decoder } = decodeAll(readFileSync(stream));
      assert.equal(lines.length, 3);
      assert.deepEqual(lines, expected, `grid ${grid}`);
      decoder.close();
    }
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test('frames expose the layers as typed arrays of the stated sizes', () => {
  const decoder = m4d.openDecoder();
  decoder.push(read(streams, 'synth_sh3_three_gops.m4d'));
  decoder.end();
  const frame = decoder.nextFrame();
  assert.equal(frame.frameIndex, 0);
  assert.equal(frame.isKeyframe, true);
  assert.equal(frame.layers, 3);
  for (const layer of [frame.static, frame.dynamic]) {
    assert.ok(layer.count > 0);
    assert.equal(layer.shDegree, 3);
    assert.equal(layer.shCoefficients, 16);
    assert.equal(layer.positions.length, 3 * layer.count);
    assert.equal(layer.logScales.length, 3 * layer.count);
    assert.equal(layer.rotations.length, 4 * layer.count);
    assert.equal(layer.opacityLogits.length, layer.count);
    assert.equal(layer.sh.length, 48 * layer.count);
    assert.ok(layer.positions.every(Number.isFinite));
  }
  const second = decoder.nextFrame();
  assert.equal(second.frameIndex, 1);
  assert.equal(second.isKeyframe, false);
  decoder.close();
  assert.throws(() => decoder.nextFrame(), /closed/);
});

test('reports the stream information', () => {
  const decoder = m4d.openDecoder();
  assert.equal(decoder.streamInfo(), null);
  decoder.push(read(streams, 'synth_sh3_three_gops.m4d'));
  decoder.end();
  while (decoder.nextFrame());
  const info = decoder.streamInfo();
  assert.equal(
    info.bitstreamVersion,
    `${define('M4D_BITSTREAM_VERSION_MAJOR')}.${define('M4D_BITSTREAM_VERSION_MINOR')}`,
  );
  assert.equal(info.shDegree, 3);
  assert.equal(info.framesDecoded, 12);
  assert.equal(info.gops, 3);
  assert.equal(info.randomAccessGops, 3);
  assert.equal(info.lastKeyframeIndex, 8);
  assert.equal(info.upAxis, null);  // the synthetic writer states no up axis
  decoder.close();
});

test('seeks to a frame among the bytes received', () => {
  const data = read(streams, 'synth_sh3_three_gops.m4d');
  const expected = expectedLines(streams, 'synth_sh3_three_gops.md5');
  const decoder = m4d.openDecoder();
  decoder.push(data.subarray(0, data.length >> 1));
  assert.equal(decoder.seek(11), false);  // not arrived yet
  decoder.push(data.subarray(data.length >> 1));
  decoder.end();
  for (const target of [6, 11, 0]) {
    assert.equal(decoder.seek(target), true);
    const frame = decoder.nextFrame();
    assert.equal(`${frame.frameIndex} ${frame.hash()}`, expected[target]);
  }
  assert.equal(decoder.seek(12), false);
  decoder.close();
});

test('a seek gives the frames from the one sought on, also where frame numbers wrap', () => {
  const name = 'edit_frame_index_wraps';  // frames 2^32 - 2, 2^32 - 1, 0, 1, 2, 3
  const expected = expectedLines(streams, `${name}.md5`);
  const decoder = m4d.openDecoder();
  decoder.push(read(streams, `${name}.m4d`));
  decoder.end();
  expected.forEach((line, i) => {
    assert.equal(decoder.seek(Number(line.split(' ')[0])), true);
    const lines = [];
    for (let f; (f = decoder.nextFrame()); ) lines.push(`${f.frameIndex} ${f.hash()}`);
    assert.deepEqual(lines, expected.slice(i));
  });
  decoder.close();
});

test('every invalid stream gives its frames and its first error, without throwing', () => {
  const want = new Map(
    read(invalid, 'EXPECTED').toString().split('\n')
      .filter((l) => l && !l.startsWith('#'))
      .map((l) => l.split(' ').slice(0, 2)));
  const names = readdirSync(invalid).filter((n) => n.endsWith('.m4d'));
  assert.equal(names.length, want.size);
  for (const name of names) {
    const base = name.slice(0, -4);
    const { lines, decoder } = decodeAll(read(invalid, name), { chunk: 1000 });
    assert.deepEqual(lines, expectedLines(invalid, `${base}.md5`), base);
    assert.equal(decoder.errors.count ? decoder.errors.firstCodeName : 'NONE', want.get(base), base);
    decoder.close();
  }
});

test('a damaged dynamic payload conceals that layer and plays every frame', () => {
  // bad_payload_crc: the first GOP's KEYFRAME_DYNAMIC is damaged (bitstream-spec 6.8).
  const decoder = m4d.openDecoder();
  decoder.push(read(invalid, 'bad_payload_crc.m4d'));
  decoder.end();
  const concealed = [];
  for (let f; (f = decoder.nextFrame()); ) concealed.push([f.frameIndex, f.concealedLayers]);
  assert.deepEqual(concealed, [[0, 2], [1, 2], [2, 2], [3, 0], [4, 0], [5, 0]]);
  assert.equal(decoder.errors.firstCodeName, 'M4D_ERR_CHECKSUM');
  decoder.close();
});

test('a stream cut inside a packet is reported as truncated once it ends', () => {
  const data = read(streams, 'enc_adaptive_gop.m4d');
  const decoder = m4d.openDecoder();
  decoder.push(data.subarray(0, 1000));
  assert.equal(decoder.nextFrame(), null);
  assert.equal(decoder.errors.count, 0);  // more bytes may come
  decoder.end();
  assert.equal(decoder.nextFrame(), null);
  assert.equal(decoder.errors.count, 1);
  assert.equal(decoder.errors.lastCodeName, 'TRUNCATED');
  assert.throws(() => decoder.push(data.subarray(1000)), /after end/);
  decoder.close();
});

test('refuses layers above maxGaussians and plays on', () => {
  const data = read(streams, 'synth_sh3_three_gops.m4d');
  const counts = [];
  const probe = m4d.openDecoder();
  probe.push(data);
  probe.end();
  for (let f; (f = probe.nextFrame()); ) counts.push(Math.max(f.static.count, f.dynamic.count));
  probe.close();
  const limit = Math.max(...counts) - 1;
  const decoder = m4d.openDecoder({ maxGaussians: limit });
  decoder.push(data);
  decoder.end();
  while (decoder.nextFrame());
  assert.ok(decoder.errors.count > 0);
  assert.equal(decoder.errors.firstCodeName, 'M4D_ERR_LIMIT');
  decoder.close();
  assert.throws(() => m4d.openDecoder({ maxGaussians: -1 }), RangeError);
});

test('every method the TypeScript declarations declare exists', async () => {
  const api = await import(new URL('m4d.mjs', moduleDir));
  const declarations = readFileSync(new URL('web/js/m4d.d.mts', root)).toString();
  let checked = 0;
  for (const [, name, body] of declarations.matchAll(/export declare class (\w+) \{([^}]*)\}/g)) {
    for (const [, member] of body.matchAll(/^  (?:readonly )?(\w+)[(:]/gm)) {
      const descriptor = Object.getOwnPropertyDescriptor(api[name].prototype, member);
      assert.ok(descriptor, `${name}.${member} is declared but not defined`);
      ++checked;
    }
  }
  for (const [, name] of declarations.matchAll(/export declare function (\w+)/g)) {
    assert.equal(typeof api[name], 'function', name);
    ++checked;
  }
  assert.ok(checked > 20, `${checked} members`);
});

test('reports its version', () => {
  assert.equal(
    m4d.version(),
    `${define('M4D_VERSION_MAJOR')}.${define('M4D_VERSION_MINOR')}.${define('M4D_VERSION_PATCH')}`,
  );
});
