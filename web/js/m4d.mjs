// m4d.mjs - the M4D decoder for JavaScript: the SDK's decoder compiled to WebAssembly
// (m4d_wasm.mjs and m4d_wasm.wasm beside this file), for browsers and Node.js.
//
//   import { loadM4d } from './m4d.mjs';
//   const m4d = await loadM4d();
//   const decoder = m4d.openDecoder();          // { layers: 'all' | 'static' | 'dynamic' }
//   decoder.push(bytes);                        // any chunks: Uint8Array or ArrayBuffer
//   decoder.end();                              // when no more bytes come
//   for (let f; (f = decoder.nextFrame()); ) {  // null: more bytes needed, or the end
//     draw(f.dynamic.positions, ...);           // Float32Array views, valid until the next call
//   }
//   decoder.close();
//
// Decoding is the native SDK's, bit for bit: frame.hash() is the normative frame hash of
// bitstream-spec 7. Damaged streams never throw: the damage is counted (decoder.errors) and
// reading resumes at the next packet header or GOP, as the spec's section 3 says.
import createM4dModule from './m4d_wasm.mjs';

const LAYER_BITS = { static: 1, dynamic: 2, all: 3 };
// The M4D_ERR_* codes of m4d.h, by value.
const ERROR_NAMES = {
  [-1]: 'M4D_ERR_AGAIN', [-2]: 'M4D_ERR_INVALID_ARG', [-3]: 'M4D_ERR_NOMEM',
  [-4]: 'M4D_ERR_BITSTREAM', [-5]: 'M4D_ERR_CHECKSUM', [-6]: 'M4D_ERR_UNSUPPORTED',
  [-7]: 'M4D_ERR_LIMIT', [-100]: 'TRUNCATED',
};

// The name of an error code ('' for 0).
export function errorCodeName(code) {
  return code === 0 ? '' : ERROR_NAMES[code] || `error ${code}`;
}
// M4dStreamInfo.up_axis (bitstream-spec 4.1): the world axis that is up, as a unit vector;
// null when the stream does not state it (before bitstream 0.9).
const UP_AXES = [null, [1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]];

const TRUNCATED = -100;  // m4dw_stream_last_error_code: the stream ends inside a packet or a frame

// Loads the module. options.wasmBinary (bytes of m4d_wasm.wasm) skips fetching it; Node.js
// reads it from beside this file.
export async function loadM4d(options = {}) {
  const moduleOptions = {};
  if (options.wasmBinary) {
    moduleOptions.wasmBinary = options.wasmBinary;
  } else if (typeof process === 'object' && process.versions && process.versions.node) {
    const { readFile } = await import('node:fs/promises');
    moduleOptions.wasmBinary = await readFile(new URL('./m4d_wasm.wasm', import.meta.url));
  }
  return new M4d(await createM4dModule(moduleOptions));
}

export class M4d {
  constructor(wasm) {
    this.wasm = wasm;
  }

  // The SDK's version string, e.g. "0.9.0".
  version() {
    return this.wasm.UTF8ToString(this.wasm._m4d_version());
  }

  // The message of an M4D_ERR_* code.
  errorString(code) {
    return code === TRUNCATED ? 'truncated' : this.wasm.UTF8ToString(this.wasm._m4d_error_string(code));
  }

  // A decoder; options.layers: 'all' (default), 'static' or 'dynamic' (the other layer's
  // packets are skipped, never decoded); options.maxGaussians: the largest Gaussian count
  // accepted in a layer (default 0: the spec's limit, 2^22), larger ones fail with
  // M4D_ERR_LIMIT before anything is allocated; set it where memory is short.
  openDecoder(options = {}) {
    const layers = LAYER_BITS[options.layers || 'all'];
    if (layers === undefined) throw new RangeError(`layers must be all, static or dynamic`);
    const maxGaussians = options.maxGaussians ?? 0;
    if (!Number.isInteger(maxGaussians) || maxGaussians < 0) throw new RangeError('maxGaussians must be a count');
    const stream = this.wasm._m4dw_stream_open(layers, maxGaussians);
    if (!stream) throw new Error('m4d: cannot open a decoder (out of memory)');
    return new M4dDecoder(this, stream);
  }

  // The SDK's renderer drawing into `canvas` (an HTMLCanvasElement with an id) through a
  // WebGL2 context it creates there. options.background: linear RGB behind the splats
  // (default black); options.shDegree: largest SH degree evaluated (default 3).
  openRenderer(canvas, options = {}) {
    if (!canvas || !canvas.id) throw new TypeError('m4d: the canvas needs an id');
    const [red, green, blue] = options.background || [0, 0, 0];
    const selector = `#${canvas.id}`;
    const size = this.wasm.lengthBytesUTF8(selector) + 1;
    const text = this.wasm._malloc(size);
    this.wasm.stringToUTF8(selector, text, size);
    const renderer = this.wasm._m4dw_renderer_open(text, red, green, blue, options.shDegree ?? 3);
    this.wasm._free(text);
    if (!renderer) throw new Error('m4d: no WebGL2 context on the canvas, or the renderer failed');
    return new M4dRenderer(this, renderer, canvas);
  }
}

// Draws decoded frames into a canvas: upload a decoder's current frame, then draw it from any
// camera (OpenCV axes: x right, y down, z forward; world to camera).
export class M4dRenderer {
  constructor(m4d, renderer, canvas) {
    this.m4d = m4d;
    this.wasm = m4d.wasm;
    this.renderer = renderer;
    this.canvas = canvas;
  }

  // Uploads the layers ('all', 'static' or 'dynamic') of the frame the decoder last returned.
  upload(decoder, layers = 'all') {
    const r = this.wasm._m4dw_renderer_upload(this.live(), decoder.live(), LAYER_BITS[layers] ?? 0);
    if (r < 0) throw new Error(`m4d: upload failed: ${this.lastError()}`);
  }

  // Draws what was uploaded. camera: { fx, fy, cx, cy, rotation (9, row-major), translation
  // (3), near (default 0.2) }, in pixels of the canvas's drawing buffer.
  draw(camera) {
    const at = this.wasm._m4dw_renderer_camera(this.live());
    const u = this.wasm.HEAPU32, f = this.wasm.HEAPF32, w = at >> 2;
    u[w] = this.canvas.width;
    u[w + 1] = this.canvas.height;
    f.set([camera.fx, camera.fy, camera.cx, camera.cy], w + 2);
    f.set(camera.rotation, w + 6);
    f.set(camera.translation, w + 15);
    f[w + 18] = camera.near ?? 0.2;
    if (this.wasm._m4dw_renderer_draw(this.renderer) < 0) {
      throw new Error(`m4d: draw failed: ${this.lastError()}`);
    }
  }

  // The last draw's splat count and stage timings in milliseconds.
  stats() {
    const at = this.wasm._m4dw_renderer_stats(this.live());
    const visible = this.wasm.HEAPU32[at >> 2];
    const ms = this.wasm.HEAPF64.subarray((at >> 3) + 1, (at >> 3) + 5);
    return { visible, projectMs: ms[0], sortMs: ms[1], uploadMs: ms[2], drawMs: ms[3] };
  }

  lastError() {
    return this.wasm.UTF8ToString(this.wasm._m4dw_renderer_last_error(this.live()));
  }

  close() {
    if (!this.renderer) return;
    this.wasm._m4dw_renderer_close(this.renderer);
    this.renderer = 0;
  }

  live() {
    if (!this.renderer) throw new Error('m4d: the renderer is closed');
    return this.renderer;
  }
}

export class M4dDecoder {
  constructor(m4d, stream) {
    this.m4d = m4d;
    this.wasm = m4d.wasm;
    this.stream = stream;
    this.scratch = this.wasm._malloc(128);  // m4d_get_stream_info, m4d_frame_hash
  }

  // Appends bytes of the stream (the next chunk, any size).
  push(bytes) {
    const data = bytes instanceof Uint8Array ? bytes : new Uint8Array(bytes);
    const at = this.wasm._m4dw_stream_reserve(this.live(), data.length);
    if (!at) throw new Error('m4d: out of memory, or push after end');
    this.wasm.HEAPU8.set(data, at);
  }

  // No more bytes come: a packet cut at the end is then counted as damage.
  end() {
    this.wasm._m4dw_stream_end(this.live());
  }

  // Decodes up to the next frame. Returns an M4dFrame, or null when more bytes are needed
  // (or, after end(), the stream is over). The previous frame is released.
  nextFrame() {
    if (!this.wasm._m4dw_stream_next_frame(this.live())) return null;
    return new M4dFrame(this);
  }

  // Restarts at the random-access point at or before frameIndex, among the bytes pushed so
  // far; nextFrame() then returns frameIndex first. Returns false when that frame has not
  // arrived yet; throws when no random-access GOP precedes it.
  seek(frameIndex) {
    const r = this.wasm._m4dw_stream_seek(this.live(), frameIndex >>> 0);
    if (r === -1) return false;
    if (r < 0) throw new Error(`m4d: cannot seek to frame ${frameIndex}: ${this.m4d.errorString(r)}`);
    return true;
  }

  // What the decoder knows of the stream (null before the first SEQUENCE_HEADER).
  streamInfo() {
    const context = this.wasm._m4dw_stream_context(this.live());
    if (this.wasm._m4d_get_stream_info(context, this.scratch) < 0) return null;
    const u = this.wasm.HEAPU32.subarray(this.scratch >> 2, (this.scratch >> 2) + 15);
    return {
      bitstreamVersion: `${u[0]}.${u[1]}`, profile: u[2], shDegree: u[3],
      fps: u[5] ? u[4] / u[5] : 0, fpsNum: u[4], fpsDen: u[5], numFrames: u[6],
      staticLayerCoded: (u[7] & 1) !== 0, framesDecoded: u[8], gops: u[9],
      randomAccessGops: u[10], lastKeyframeIndex: u[11], lastRandomAccessIndex: u[12],
      upAxis: UP_AXES[u[13]] ?? null,
    };
  }

  // Damage met so far: how many errors, the first one's code, the last one's byte offset,
  // code and message. Codes are M4D_ERR_* values (names: M4D_ERR_BITSTREAM...), or -100,
  // named TRUNCATED, when the stream ends inside a packet or a frame (spec 9).
  get errors() {
    const s = this.live();
    const code = this.wasm._m4dw_stream_last_error_code(s);
    const first = this.wasm._m4dw_stream_first_error_code(s);
    return {
      count: this.wasm._m4dw_stream_error_count(s),
      firstCode: first,
      firstCodeName: errorCodeName(first),
      lastOffset: this.wasm._m4dw_stream_last_error_offset(s),
      lastCode: code,
      lastCodeName: errorCodeName(code),
      lastMessage: this.wasm.UTF8ToString(this.wasm._m4dw_stream_last_error_message(s)),
    };
  }

  // Replaces the static layer by the static layer of the frame `source` (another decoder)
  // last returned, from the next frame on; null restores the stream's own.
  setBackground(source) {
    const r = this.wasm._m4dw_stream_set_background(this.live(), source ? source.live() : 0);
    if (r < 0) throw new Error(`m4d: cannot set the background (${errorCodeName(r)})`);
  }

  // Bytes passed over while resynchronising after damage.
  get skippedBytes() {
    return this.wasm._m4dw_stream_skipped_bytes(this.live());
  }

  // Bytes pushed so far (all are kept, for seeking).
  get bufferedBytes() {
    return this.wasm._m4dw_stream_buffered_bytes(this.live());
  }

  // Frees the decoder and its frame.
  close() {
    if (!this.stream) return;
    this.wasm._m4dw_stream_close(this.stream);
    this.wasm._free(this.scratch);
    this.stream = 0;
  }

  live() {
    if (!this.stream) throw new Error('m4d: the decoder is closed');
    return this.stream;
  }
}

// A decoded frame. Its arrays view the module's memory: valid until the decoder's next call.
export class M4dFrame {
  constructor(decoder) {
    const wasm = decoder.wasm, s = decoder.stream;
    this.decoder = decoder;
    this.frameIndex = wasm._m4dw_frame_index(s) >>> 0;  // u32: frame numbers wrap at 2^32
    this.isKeyframe = wasm._m4dw_frame_is_keyframe(s) !== 0;
    this.layers = wasm._m4dw_frame_layers(s);
    this.concealedLayers = wasm._m4dw_frame_concealed_layers(s);
    this.static = layerView(wasm, wasm._m4dw_frame_layer(s, 1));
    this.dynamic = layerView(wasm, wasm._m4dw_frame_layer(s, 2));
  }

  // The normative frame hash (bitstream-spec 7), as 32 hex digits.
  hash() {
    const { wasm, scratch, stream } = this.decoder;
    wasm._m4d_frame_hash(wasm._m4dw_frame(stream), scratch);
    return Array.from(wasm.HEAPU8.subarray(scratch, scratch + 16), (b) => b.toString(16).padStart(2, '0')).join('');
  }
}

// One layer's Gaussians (M4dGaussians: eight 32-bit words in wasm32), values as coded.
function layerView(wasm, address) {
  const w = wasm.HEAPU32.subarray(address >> 2, (address >> 2) + 8);
  const count = w[0], coefficients = w[2];
  const floats = (at, perGaussian) => (count ? wasm.HEAPF32.subarray(at >> 2, (at >> 2) + count * perGaussian) : new Float32Array(0));
  return {
    count,
    shDegree: w[1],
    shCoefficients: coefficients,
    positions: floats(w[3], 3),
    logScales: floats(w[4], 3),
    rotations: floats(w[5], 4),
    opacityLogits: floats(w[6], 1),
    sh: floats(w[7], 3 * coefficients),
  };
}
