// m4d_worker.mjs - the M4D decoder in a Web Worker (a module worker): receives stream bytes,
// posts decoded frames as SplatFrames (splat_frame.mjs) with their buffers transferred. The
// static layer is sent only when it changes: on the first frame, after a seek, and at a
// keyframe whose static layer differs (a random-access keyframe or a STATIC_UPDATE).
// Page side: worker_decoder.mjs (M4dWorkerDecoder), which speaks this protocol:
//
//   request  { id, type: 'open', moduleUrl?, wasmUrl?, wasmBinary?, layers?, maxGaussians? }
//            { id, type: 'push', bytes }  { id, type: 'end' }  { id, type: 'seek', frame }
//            { id, type: 'next' }  { id, type: 'close' }
//   reply    { id, ok: true, result }  or  { id, ok: false, error }
//            'next' result: { frame: SplatFrame | null, ended, info, errors, decodeMs }
//
// Requests are handled one at a time, in the order they arrive.
import { SplatFrameMaker, transferablesOf } from './splat_frame.mjs';

let m4d = null;
let decoder = null;
let ended = false;
let frames = new SplatFrameMaker();  // sets staticChanged from the static layer last sent

async function open(message) {
  if (decoder) throw new Error('m4d worker: already open');
  const moduleUrl = message.moduleUrl ? new URL(message.moduleUrl, self.location.href) : new URL('./m4d.mjs', import.meta.url);
  const { loadM4d } = await import(moduleUrl.href);
  let wasmBinary = message.wasmBinary;
  if (!wasmBinary && message.wasmUrl) {
    const response = await fetch(new URL(message.wasmUrl, self.location.href));
    if (!response.ok) throw new Error(`m4d worker: ${message.wasmUrl}: HTTP ${response.status}`);
    wasmBinary = await response.arrayBuffer();
  }
  m4d = await loadM4d(wasmBinary ? { wasmBinary } : {});
  decoder = m4d.openDecoder({ layers: message.layers, maxGaussians: message.maxGaussians });
  return { version: m4d.version() };
}

function live() {
  if (!decoder) throw new Error('m4d worker: not open');
  return decoder;
}

// Decodes the next frame; its SplatFrame and the buffers to transfer.
function next() {
  const d = live();
  const start = performance.now();
  const frame = d.nextFrame();
  if (!frame) {
    return { result: { frame: null, ended, info: d.streamInfo(), errors: d.errors, decodeMs: performance.now() - start } };
  }
  const splat = frames.make(frame);
  const decodeMs = performance.now() - start;
  return {
    result: { frame: splat, ended, info: d.streamInfo(), errors: d.errors, decodeMs },
    transfer: transferablesOf(splat),
  };
}

async function handle(message) {
  switch (message.type) {
    case 'open':
      return { result: await open(message) };
    case 'push': {
      const d = live();
      d.push(message.bytes);
      return { result: { bufferedBytes: d.bufferedBytes } };
    }
    case 'end':
      live().end();
      ended = true;
      return { result: null };
    case 'seek': {
      if (!Number.isInteger(message.frame) || message.frame < 0) throw new RangeError(`m4d worker: bad frame ${message.frame}`);
      const done = live().seek(message.frame);
      if (done) frames.reset();
      return { result: done };
    }
    case 'next':
      return next();
    case 'close':
      decoder?.close();
      decoder = null;
      frames = new SplatFrameMaker();
      return { result: null };
    default:
      throw new Error(`m4d worker: unknown request ${message.type}`);
  }
}

let queue = Promise.resolve();
self.onmessage = (event) => {
  const message = event.data || {};
  queue = queue.then(async () => {
    try {
      const { result, transfer } = await handle(message);
      self.postMessage({ id: message.id, ok: true, result }, transfer || []);
    } catch (error) {
      self.postMessage({ id: message.id, ok: false, error: error && error.message ? error.message : String(error) });
    }
  });
};
