#!/usr/bin/env node
// Adaptive bitrate under throttling: plays the renditions of MANIFEST (m4d encode
// --renditions) through AbrController (web/js/abr_controller.mjs) from a local server whose
// bandwidth is FAST, then SLOW from GOP --slow-from to --slow-until, then FAST again, and
// prints the renditions (bytes, bandwidth, PSNR from the encoder's reports beside them), the
// switches with the time from the rate change to the switch, and the stalls. Rates default to
// 10x and 1x the highest rendition's bandwidth.
//
//   node web/bench/abr_switching.mjs OUT.manifest.json [--slow-from 3] [--slow-until 6]
//                                    [--slow BYTES_PER_S] [--fast BYTES_PER_S] [--buffer S]
import { existsSync, readFileSync } from 'node:fs';
import { basename, dirname, join } from 'node:path';
import { parseArgs } from 'node:util';
import { AbrController, validateManifest } from '../js/abr_controller.mjs';
import { throttledServer } from '../tools/throttled_server.mjs';

const { values, positionals } = parseArgs({
  allowPositionals: true,
  options: {
    'slow-from': { type: 'string', default: '3' },
    'slow-until': { type: 'string', default: '6' },
    slow: { type: 'string' },
    fast: { type: 'string' },
    buffer: { type: 'string' },
  },
});
if (positionals.length !== 1) {
  console.error('usage: abr_switching.mjs OUT.manifest.json [--slow-from G] [--slow-until G] ' +
    '[--slow B/s] [--fast B/s] [--buffer S]');
  process.exit(2);
}
const manifestPath = positionals[0];
const manifest = validateManifest(JSON.parse(readFileSync(manifestPath, 'utf8')));
const { loadM4d } = await import(new URL('../../build/web/module/m4d.mjs', import.meta.url));
const m4d = await loadM4d();
const high = manifest.renditions.at(-1);
const slow = Number(values.slow ?? high.bandwidth / 8), fast = Number(values.fast ?? 10 * slow);
const slowFrom = Number(values['slow-from']), slowUntil = Number(values['slow-until']);
const gops = manifest.renditions[0].gops;
const gopSeconds = gops[0].frames / manifest.fps;

console.log('| rendition | bytes | kbit/s | PSNR dB (held-out, encoder report) |');
console.log('|---|---:|---:|---:|');
for (const r of manifest.renditions) {
  const report = join(dirname(manifestPath), `${r.url}.json`);
  const psnr = existsSync(report) ? JSON.parse(readFileSync(report, 'utf8')).summary.psnr : NaN;
  console.log(`| ${r.id} | ${r.bytes} | ${(r.bandwidth / 1000).toFixed(1)} | ${psnr.toFixed(2)} |`);
}

const server = await throttledServer(dirname(manifestPath));
const abr = new AbrController({
  manifestUrl: `${server.base}${basename(manifestPath)}`,
  openDecoder: () => m4d.openDecoder(),
  maxBufferSeconds: Number(values.buffer ?? 3 * gopSeconds),
});
await abr.load();
const rateChanges = [];  // { gop, time }: when the rate changed (ms since the first fetch)
let t0 = 0;
const rows = [];
for (let g = 0; g < gops.length; ++g) {
  const rate = g >= slowFrom && g < slowUntil ? slow : fast;
  if (g === 0) t0 = performance.now();
  if (g > 0 && rate !== server.rate) rateChanges.push({ gop: g, time: performance.now() - t0 });
  server.rate = rate;
  rows.push({ rate, ...(await abr.nextGop()) });
}
abr.close();
await server.close();

console.log(`\nslow ${(8 * slow / 1000).toFixed(1)} kbit/s, fast ${(8 * fast / 1000).toFixed(1)} ` +
  `kbit/s, GOP ${(gopSeconds * 1000).toFixed(0)} ms, buffer ${abr.options.maxBufferSeconds.toFixed(2)} s\n`);
console.log('| GOP | frame | rate kbit/s | rendition | fetch ms | measured kbit/s | stall ms |');
console.log('|---:|---:|---:|---|---:|---:|---:|');
for (const r of rows) {
  console.log(`| ${r.gop} | ${r.frame} | ${(8 * r.rate / 1000).toFixed(0)} | ${r.rendition} | ` +
    `${(r.seconds * 1000).toFixed(1)} | ${(r.throughput / 1000).toFixed(0)} | ${r.stallMs.toFixed(1)} |`);
}
console.log('\n| switch at frame | from | to | estimate kbit/s | after the rate change |');
console.log('|---:|---|---|---:|---:|');
for (const s of abr.switchLog) {
  const change = rateChanges.filter((c) => c.time <= s.time).at(-1);
  const after = change
    ? `${(s.time - change.time).toFixed(0)} ms, ${(s.frame - gops[change.gop].frame) / gops[0].frames} GOP`
    : 'start';
  console.log(`| ${s.frame} | ${s.from} | ${s.to} | ${(s.throughput / 1000).toFixed(0)} | ${after} |`);
}
const st = abr.stalls;
console.log(`\nstalls: ${st.count}, ${st.ms.toFixed(1)} ms in all, longest ` +
  `${Math.max(0, ...st.list.map((s) => s.ms)).toFixed(1)} ms`);
