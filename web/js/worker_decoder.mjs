// worker_decoder.mjs - the page side of m4d_worker.mjs: the M4D decoder running in a Web
// Worker, behind a promise API. Frames arrive as SplatFrames (splat_frame.mjs) whose arrays
// were transferred, not copied, from the worker.
//
//   const decoder = new M4dWorkerDecoder();       // { workerUrl, moduleUrl, wasmUrl, layers }
//   await decoder.open();
//   decoder.push(chunk);                          // as bytes arrive; then decoder.end()
//   for (let f; (f = await decoder.nextFrame()); ) draw(f);
//   decoder.close();
//
// A worker that dies (its script fails to load, or it throws outside a request) rejects every
// waiting call and every later one: nothing waits forever on it.

// The M4D decoder in a Web Worker. options: workerUrl (default m4d_worker.mjs beside this
// file), moduleUrl (m4d.mjs for the worker; default beside the worker), wasmUrl or wasmBinary
// (default: m4d_wasm.wasm beside m4d_wasm.mjs), layers ('all', 'static', 'dynamic'),
// maxGaussians.
export class M4dWorkerDecoder {
  constructor(options = {}) {
    this.options = options;
    this.worker = null;
    this.pending = new Map();
    this.nextId = 1;
    this.failure = null;
    /** The stream's M4dStreamInfo as of the last frame request (null before the header). */
    this.info = null;
    /** The decoder's M4dErrors as of the last frame request. */
    this.errors = null;
    /** True once end() was called and nextFrame() found no more frames. */
    this.ended = false;
    /** Milliseconds the worker spent decoding the last frame. */
    this.lastDecodeMs = 0;
  }

  // Starts the worker and loads the decoder in it; resolves with { version }.
  async open() {
    if (this.worker) throw new Error('m4d: the worker decoder is already open');
    if (this.failure) throw this.failure;
    const url = this.options.workerUrl || new URL('./m4d_worker.mjs', import.meta.url);
    try {
      this.worker = new Worker(url, { type: 'module' });
    } catch (error) {
      this.fail(new Error(`m4d: cannot start the worker ${url}: ${error.message}`));
      throw this.failure;
    }
    this.worker.onmessage = (event) => this.receive(event.data);
    this.worker.onerror = (event) => {
      if (event.preventDefault) event.preventDefault();
      this.fail(new Error(`m4d: the decoder worker died${event.message ? `: ${event.message}` : ' (its script did not load)'}`));
    };
    this.worker.onmessageerror = () => this.fail(new Error('m4d: a message from the decoder worker could not be read'));
    const { moduleUrl, wasmUrl, wasmBinary, layers, maxGaussians } = this.options;
    const absolute = (u) => (u ? new URL(u, globalThis.location?.href).href : undefined);
    return this.call('open', { moduleUrl: absolute(moduleUrl), wasmUrl: absolute(wasmUrl), wasmBinary, layers, maxGaussians });
  }

  // Appends stream bytes. A copy of them is sent (only the bytes given, not the rest of their
  // buffer); options.transfer: true moves the ArrayBuffer instead when `bytes` spans all of it
  // (the caller's array is then detached). Resolves with { bufferedBytes }.
  push(bytes, options = {}) {
    const data = bytes instanceof Uint8Array ? bytes : new Uint8Array(bytes);
    const whole = data.byteOffset === 0 && data.byteLength === data.buffer.byteLength;
    const sent = options.transfer && whole ? data : data.slice();
    return this.call('push', { bytes: sent }, [sent.buffer]);
  }

  // No more bytes come.
  end() {
    return this.call('end', {});
  }

  // Restarts at the random-access point at or before `frame`; the next frame is `frame`, with
  // its static layer. Resolves false when that frame's bytes have not arrived yet.
  seek(frame) {
    return this.call('seek', { frame });
  }

  // The next frame as a SplatFrame, or null when more bytes are needed (or, after end(), the
  // stream is over: `ended` then turns true).
  async nextFrame() {
    const { frame, ended, info, errors, decodeMs } = await this.call('next', {});
    this.info = info;
    this.errors = errors;
    this.lastDecodeMs = decodeMs;
    this.ended = !frame && ended;
    return frame;
  }

  // The stream's M4dStreamInfo as last reported (sync; null before the first frame request).
  streamInfo() {
    return this.info;
  }

  // Stops the worker; waiting and later calls reject.
  close() {
    if (!this.worker) return;
    this.worker.terminate();
    this.worker = null;
    this.fail(new Error('m4d: the worker decoder is closed'));
  }

  call(type, payload, transfer = []) {
    if (this.failure) return Promise.reject(this.failure);
    if (!this.worker) return Promise.reject(new Error('m4d: the worker decoder is not open'));
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      try {
        this.worker.postMessage({ id, type, ...payload }, transfer);
      } catch (error) {
        this.pending.delete(id);
        reject(error);
      }
    });
  }

  receive(message) {
    const waiting = message && this.pending.get(message.id);
    if (!waiting) return;
    this.pending.delete(message.id);
    if (message.ok) waiting.resolve(message.result);
    else waiting.reject(new Error(message.error));
  }

  fail(error) {
    if (!this.failure) this.failure = error;
    for (const { reject } of this.pending.values()) reject(this.failure);
    this.pending.clear();
    if (this.worker) {
      this.worker.terminate();
      this.worker = null;
    }
  }
}
