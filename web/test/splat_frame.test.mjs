// Tests of the SplatFrame layout and conversions (web/js/splat_frame.mjs) in Node.js, on the
// main-thread decoder's frames (build/web/module, scripts/build_web.sh) and on hand-made layers.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { test } from 'node:test';
import {
  SH_C0, copySplatLayer, layersEqual, linearScales, normalisedRotationsXyzw, opacities, rgbFromShDc,
  DecoderFrameSource, SplatFrameMaker, splatFrameFromDecoder, transferablesOf,
} from '../js/splat_frame.mjs';
import { PlayerCore } from '../js/player_core.mjs';

const root = new URL('../../', import.meta.url);
const { loadM4d } = await import(new URL('build/web/module/m4d.mjs', root));

test('copies a decoded frame into owned arrays and lists their buffers', async () => {
  const m4d = await loadM4d();
  const decoder = m4d.openDecoder();
  decoder.push(readFileSync(new URL('conformance/streams/enc_adaptive_gop.m4d', root)));
  decoder.end();
  const view = decoder.nextFrame();
  const frame = splatFrameFromDecoder(view, { staticChanged: true });
  assert.equal(frame.frameIndex, 0);
  assert.equal(frame.isKeyframe, true);
  assert.equal(frame.layers, 3);
  assert.equal(frame.concealedLayers, 0);
  assert.equal(frame.staticChanged, true);
  assert.ok(layersEqual(frame.static, view.static) && layersEqual(frame.dynamic, view.dynamic));
  for (const layer of [frame.static, frame.dynamic]) {
    assert.equal(layer.positions.length, 3 * layer.count);
    assert.equal(layer.sh.length, 3 * layer.shCoefficients * layer.count);
    assert.notEqual(layer.positions.buffer, view.dynamic.positions.buffer);  // not wasm memory
  }
  assert.equal(transferablesOf(frame).length, 10);
  const inter = splatFrameFromDecoder(decoder.nextFrame(), { staticChanged: false });
  assert.equal(inter.static, null);
  assert.equal(transferablesOf(inter).length, 5);
  assert.equal(layersEqual(frame.dynamic, inter.dynamic), false);
  // The copy outlives the decoder.
  decoder.close();
  assert.ok(Number.isFinite(frame.dynamic.positions[0]));
});

test('SplatFrameMaker sends the static layer when it changes: first frame, static update, seek', async () => {
  const m4d = await loadM4d();
  const decoder = m4d.openDecoder();
  decoder.push(readFileSync(new URL('conformance/streams/enc_adaptive_gop.m4d', root)));
  decoder.end();
  const maker = new SplatFrameMaker();
  const made = [];
  for (let f; (f = decoder.nextFrame());) made.push(maker.make(f));
  // GOPs of 2; frames 2 and 4 are keyframes with a STATIC_UPDATE (843, 990, 1230 static Gaussians).
  assert.deepEqual(made.map((f) => f.staticChanged), [true, false, true, false, true, false]);
  assert.deepEqual(made.filter((f) => f.static).map((f) => f.static.count), [843, 990, 1230]);
  assert.ok(layersEqual(maker.lastStatic, made[4].static));
  assert.notEqual(maker.lastStatic.positions.buffer, made[4].static.positions.buffer);  // its own copy
  // After a seek the next frame carries its static layer even when it did not change.
  assert.equal(decoder.seek(5), true);
  maker.reset();
  const after = maker.make(decoder.nextFrame());
  assert.equal(after.frameIndex, 5);
  assert.equal(after.staticChanged, true);
  assert.ok(layersEqual(after.static, made[4].static));
  decoder.close();
});

test('DecoderFrameSource feeds PlayerCore from a main-thread decoder', async () => {
  const m4d = await loadM4d();
  const decoder = m4d.openDecoder();
  decoder.push(readFileSync(new URL('conformance/streams/enc_adaptive_gop.m4d', root)));
  decoder.end();
  const source = new DecoderFrameSource(decoder);
  const core = new PlayerCore(source, { maxQueue: 1 });
  const flush = async () => { for (let i = 0; i < 10; ++i) await new Promise((done) => setImmediate(done)); };
  const shown = [];
  await flush();
  shown.push(core.tick(0));
  for (let f = 1; f < 6; ++f) {
    core.step();
    await flush();
    shown.push(core.tick(f));
  }
  assert.deepEqual(shown.map((f) => f.frameIndex), [0, 1, 2, 3, 4, 5]);
  assert.deepEqual(shown.map((f) => f.staticChanged), [true, false, true, false, true, false]);
  assert.equal(source.streamInfo().fps, 30);
  await flush();
  assert.equal(core.ended, true);
  assert.equal(await core.seek(3), true);
  await flush();
  const again = core.tick(100);
  assert.equal(again.frameIndex, 3);
  assert.equal(again.staticChanged, true);
  assert.equal(again.static.count, 990);
  assert.throws(() => new DecoderFrameSource({}), /needs nextFrame\(\) and seek\(\)/);
  decoder.close();
});

test('converts to the layouts viewers take', () => {
  const layer = {
    count: 2, shDegree: 1, shCoefficients: 4,
    positions: new Float32Array(6),
    logScales: new Float32Array([0, Math.log(2), -1, 1, 0, 0]),
    rotations: new Float32Array([2, 0, 0, 0, 0, 0, 0, 0]),  // w x y z; the second is zero
    opacityLogits: new Float32Array([0, 100]),
    sh: new Float32Array(24).map((_, i) => (i < 3 ? [1, -1, 0][i] : i)),
  };
  const close = (a, b) => a.forEach((v, i) => assert.ok(Math.abs(v - b[i]) < 1e-6, `${i}: ${v} vs ${b[i]}`));
  close(linearScales(layer), [1, 2, Math.exp(-1), Math.E, 1, 1]);
  close(opacities(layer), [0.5, 1]);
  close(normalisedRotationsXyzw(layer), [0, 0, 0, 1, 0, 0, 0, 1]);
  close(rgbFromShDc(layer), [0.5 + SH_C0, 0.5 - SH_C0, 0.5, 0.5 + SH_C0 * 12, 0.5 + SH_C0 * 13, 0.5 + SH_C0 * 14]);
  const out = new Float32Array(8);
  assert.equal(normalisedRotationsXyzw(layer, out), out);
  const copy = copySplatLayer(layer);
  assert.ok(layersEqual(copy, layer));
  copy.sh[2] = -0;  // equal as a number, not bit for bit
  assert.equal(layersEqual(copy, layer), false);
});
