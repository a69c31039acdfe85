#!/usr/bin/env node
// The WebAssembly side of m4d_packet_times (bench/packet_decode_times.cc): decode time of
// each packet through the module's exports of the public C API, one thread, the best of N
// decodes; the same output lines "<row> <count> <median ms> <mean ms>".
//
//   node web/bench/packet_decode_times.mjs STREAM [--repeat N]
import { readFileSync } from 'node:fs';
import { parseArgs } from 'node:util';

const { values, positionals } = parseArgs({ allowPositionals: true, options: { repeat: { type: 'string', default: '5' } } });
const repeat = Number(values.repeat);
if (positionals.length !== 1 || !(repeat >= 1)) {
  console.error('usage: packet_decode_times.mjs STREAM [--repeat N]');
  process.exit(2);
}
const { loadM4d } = await import(new URL('../../build/web/module/m4d.mjs', import.meta.url));
const w = (await loadM4d()).wasm;
const TYPES = ['', 'sequence_header', 'keyframe_static', 'keyframe_dynamic', 'mlp_weights',
  'motion_grid', 'compensation', 'static_update', 'appearance'];

const data = readFileSync(positionals[0]);
const stream = w._malloc(data.length);
w.HEAPU8.set(data, stream);
const info = w._malloc(64), settings = w._malloc(256), frame = w._malloc(512), handle = w._malloc(4);

// M4dPacketInfo in wasm32: type, frame_index, end_of_frame, payload_size, packet_size.
const packets = [];
for (let pos = 0; pos < data.length;) {
  if (w._m4d_parse_packet_header(stream + pos, data.length - pos, info) !== 0) break;
  const u = w.HEAPU32.subarray(info >> 2, (info >> 2) + 5);
  packets.push({ offset: pos, size: u[4], type: TYPES[u[0]] || 'unknown', frame: u[1] });
  pos += u[4];
}

function decodeOnce() {
  w._m4d_default_settings(settings);
  if (w._m4d_open(handle, settings) < 0) throw new Error('m4d_open failed');
  const context = w.HEAPU32[handle >> 2];
  const ms = packets.map((p) => {
    const start = performance.now();
    let r = w._m4d_send_packet(context, stream + p.offset, p.size);
    while (w._m4d_get_frame(context, frame) === 0) w._m4d_frame_unref(frame);
    if (r === -1) r = w._m4d_send_packet(context, stream + p.offset, p.size);
    if (r !== 0) throw new Error(`${positionals[0]} does not decode cleanly (${r})`);
    return performance.now() - start;
  });
  w._m4d_close(handle);
  return ms;
}

const best = packets.map(() => Infinity);
for (let r = 0; r < repeat; ++r) decodeOnce().forEach((ms, k) => { best[k] = Math.min(best[k], ms); });
const rows = new Map(), frames = new Map(), keyframes = new Set();
const add = (name, v) => rows.set(name, [...(rows.get(name) || []), v]);
packets.forEach((p, k) => {
  add(p.type, best[k]);
  frames.set(p.frame, (frames.get(p.frame) || 0) + best[k]);
  if (p.type === 'keyframe_dynamic') keyframes.add(p.frame);
});
for (const [index, total] of frames) add(keyframes.has(index) ? 'keyframe' : 'inter_frame', total);
for (const name of [...rows.keys()].sort()) {
  const v = rows.get(name).sort((a, b) => a - b);
  const mean = v.reduce((a, b) => a + b, 0) / v.length;
  console.log(`${name} ${v.length} ${v[v.length >> 1].toFixed(3)} ${mean.toFixed(3)}`);
}
