#!/usr/bin/env node
// m4d_decode.mjs: the conformance runner's command-line contract (conformance/README.md) for
// the WebAssembly decoder under Node.js. Prints "<frame_index> <md5>" per decoded frame and
// exits 0 for a valid stream, 1 when the stream was damaged (errors on stderr, the first also
// as "first_error NAME"), 2 on misuse.
//
//   node web/tools/m4d_decode.mjs [--layers all|static|dynamic] [--chunk BYTES] STREAM
//
// The stream is pushed in chunks of --chunk bytes (default 65536), as a page receives it.
import { readFileSync } from 'node:fs';
import { parseArgs } from 'node:util';

const usage = 'usage: m4d_decode.mjs [--layers all|static|dynamic] [--chunk BYTES] [--module DIR] STREAM';
let args;
try {
  args = parseArgs({
    allowPositionals: true,
    options: {
      layers: { type: 'string', default: 'all' },
      chunk: { type: 'string', default: '65536' },
      module: { type: 'string', default: new URL('../../build/web/module/', import.meta.url).pathname },
    },
  });
} catch (e) {
  console.error(`${e.message}\n${usage}`);
  process.exit(2);
}
const chunk = Number(args.values.chunk);
if (args.positionals.length !== 1 || !['all', 'static', 'dynamic'].includes(args.values.layers) ||
    !Number.isInteger(chunk) || chunk < 1) {
  console.error(usage);
  process.exit(2);
}

const { loadM4d } = await import(new URL('m4d.mjs', `file://${args.values.module.replace(/\/?$/, '/')}`));
let data;
try {
  data = readFileSync(args.positionals[0]);
} catch (e) {
  console.error(`m4d_decode.mjs: cannot read ${args.positionals[0]}: ${e.message}`);
  process.exit(2);
}

const m4d = await loadM4d();
const decoder = m4d.openDecoder({ layers: args.values.layers });
const lines = [];
let reported = 0;
// The contract's line for the first error: "first_error NAME" (conformance/README.md).
const report = () => {
  const e = decoder.errors;
  if (e.count > 0 && reported === 0) console.error(`first_error ${e.firstCodeName}`);
  if (e.count > reported) {
    console.error(`m4d_decode.mjs: byte ${e.lastOffset}: error ${e.lastCode} (${e.lastCodeName}): ${e.lastMessage}`);
    reported = e.count;
  }
};
const drain = () => {
  for (let f; (f = decoder.nextFrame()); report()) lines.push(`${f.frameIndex} ${f.hash()}\n`);
  report();
};
for (let at = 0; at < data.length; at += chunk) {
  decoder.push(data.subarray(at, Math.min(at + chunk, data.length)));
  drain();
}
decoder.end();
drain();
process.stdout.write(lines.join(''));
const { count } = decoder.errors;
const skipped = decoder.skippedBytes;
decoder.close();
if (lines.length === 0) console.error('m4d_decode.mjs: no frame decoded');
process.exit(count > 0 || skipped > 0 || lines.length === 0 ? 1 : 0);
