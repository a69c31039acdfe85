// Streaming an M4D stream by GOP over HTTP: the player fetches the stream's GOP index (the
// sidecar STREAM.m4d.gops.json that `m4d_probe --gop-index -o` writes), then only the GOPs it
// plays, each with one HTTP Range request whose body is pushed to the decoder as it arrives,
// so the first frame comes out as soon as the first GOP's keyframe is in (the decoder outputs a
// keyframe at its last packet; no inter frame is needed), before the rest of the GOP arrives.
// GOPs ahead are requested as playback reaches them (readAhead), and seek(frame) fetches from
// the random-access GOP at or before the frame only: nothing before it, nothing twice (the
// bytes of every GOP fetched are kept).
//
// Seeking opens a fresh decoder (M4d.openDecoder) and pushes it the GOPs from the random-access
// point on: an M4dDecoder keeps every byte pushed as one stream and seeks among them
// (M4dDecoder.seek), so bytes pushed from another offset would join GOPs that do not follow
// each other. The frames before the target are decoded and dropped, as M4dDecoder.seek does.

/** The GOP index's format name and version (m4d_probe --gop-index). */
export const GOP_INDEX_FORMAT = 'm4d-gop-index';
export const GOP_INDEX_VERSION = 1;

// An error of GopStreamer: an HTTP failure, a server without range requests, an index that is
// not one or does not match the stream.
export class GopStreamError extends Error {
  constructor(message) {
    super(`m4d stream: ${message}`);
    this.name = 'GopStreamError';
  }
}

// Checks a parsed GOP index (the contract of m4d_probe --gop-index): its fields, and GOPs that
// cover the stream without gaps, the first random-access. Returns it; throws GopStreamError.
export function checkGopIndex(index, where = 'the GOP index') {
  const fail = (what) => {
    throw new GopStreamError(`${where} ${what}`);
  };
  if (!index || index.format !== GOP_INDEX_FORMAT) fail(`is not an ${GOP_INDEX_FORMAT}`);
  if (index.version !== GOP_INDEX_VERSION) fail(`has version ${index.version}, not ${GOP_INDEX_VERSION}`);
  const { gops } = index;
  if (!Array.isArray(gops) || gops.length === 0) fail('lists no GOP');
  if (!gops[0].random_access) fail('does not start with a random-access GOP');
  let offset = 0;
  let frames = 0;
  for (const [i, g] of gops.entries()) {
    if (!(Number.isSafeInteger(g.offset) && Number.isSafeInteger(g.bytes) && g.bytes > 0 &&
          Number.isSafeInteger(g.frames) && g.frames > 0 && Number.isSafeInteger(g.frame))) {
      fail(`has a malformed GOP ${i}`);
    }
    if (g.offset !== offset) fail(`has a gap or an overlap at GOP ${i} (offset ${g.offset}, expected ${offset})`);
    offset += g.bytes;
    frames += g.frames;
  }
  if (offset !== index.stream_bytes) fail(`covers ${offset} bytes, not its stream_bytes ${index.stream_bytes}`);
  if (frames !== index.frames) fail(`counts ${frames} frames in its GOPs, not its frames ${index.frames}`);
  return index;
}

// Plays a stream over HTTP by GOP (see the top of this file). Open with GopStreamer.open.
export class GopStreamer {
  // Use GopStreamer.open.
  constructor({ m4d, url, index, layers = 'all', readAhead = 1, fetch: fetchFn }) {
    this.m4d = m4d;
    this.url = url;
    this.index = index;
    this.layers = layers;
    this.readAhead = Math.max(0, readAhead | 0);
    this.fetchFn = fetchFn;
    this.gops = index.gops;
    /** Body bytes received, over every request (index included). */
    this.bytesFetched = 0;
    /** The ranges requested, in order: { gop, start, end } (inclusive). */
    this.requests = [];
    this.entries = new Map();  // GOP number -> { chunks, received, done, error, wakers }
    this.closed = false;
    this.restart(0, null);
  }

  // Fetches the index (indexUrl, default url + '.gops.json') and checks it; resolves with a
  // streamer that has fetched nothing of the stream yet. `m4d` is the loaded module (loadM4d);
  // `layers` goes to its decoders; `readAhead` is how many GOPs past the one playing are
  // requested (default 1); `fetch` replaces globalThis.fetch.
  static async open({ m4d, url, indexUrl, layers = 'all', readAhead = 1, fetch: fetchFn }) {
    const doFetch = fetchFn ?? globalThis.fetch.bind(globalThis);
    const where = String(indexUrl ?? `${url}.gops.json`);
    let response;
    try {
      response = await doFetch(where);
    } catch (error) {
      throw new GopStreamError(`cannot fetch the GOP index ${where}: ${error.message}`);
    }
    if (!response.ok) throw new GopStreamError(`the GOP index ${where}: HTTP ${response.status}`);
    const text = await response.text();
    let index;
    try {
      index = JSON.parse(text);
    } catch {
      throw new GopStreamError(`the GOP index ${where} is not JSON`);
    }
    checkGopIndex(index, `the GOP index ${where}`);
    const streamer = new GopStreamer({ m4d, url, index, layers, readAhead, fetch: doFetch });
    streamer.bytesFetched += new TextEncoder().encode(text).length;
    return streamer;
  }

  /** Frames in the stream, as the index counts them. */
  get frames() {
    return this.index.frames;
  }

  /** Frame rate the index gives. */
  get fps() {
    return this.index.fps;
  }

  // The first GOP number at or after `from` holding frame `frame` (a frame_index; frame
  // numbers wrap at 2^32), or -1.
  gopOf(frame, from = 0) {
    for (let g = from; g < this.gops.length; ++g) {
      if (((frame - this.gops[g].frame) >>> 0) < this.gops[g].frames) return g;
    }
    return -1;
  }

  // The random-access GOP at or before the GOP holding `frame`; throws RangeError for a frame
  // the stream does not hold.
  randomAccessGopOf(frame) {
    let g = this.gopOf(frame);
    if (g < 0) throw new RangeError(`m4d stream: no frame ${frame} in the stream (${this.frames} frames)`);
    while (!this.gops[g].random_access) --g;
    return g;
  }

  // Starts decoding at GOP `gop` (random-access) with a fresh decoder; frames before `target`
  // (if given) are dropped.
  restart(gop, target) {
    if (this.decoder) this.decoder.close();
    this.decoder = this.m4d.openDecoder({ layers: this.layers });
    this.cursor = gop;       // the GOP being pushed to the decoder
    this.playing = gop;      // the GOP of the last frame output
    this.pushedChunks = 0;   // of that GOP's chunks
    this.ended = false;
    this.target = target;
  }

  // Moves playback to frame `frame`: the next nextFrame() returns it (call it between
  // nextFrame calls, not while one is pending). Fetches (later, as
  // nextFrame needs them) the GOPs from its random-access GOP on, none before; GOPs already
  // fetched are not fetched again. Throws RangeError for a frame the stream does not hold.
  seek(frame) {
    if (this.closed) throw new GopStreamError('the streamer is closed');
    const gop = this.randomAccessGopOf(frame);
    this.restart(gop, frame);
  }

  // The next frame in stream order (an M4dFrame of the decoder, valid until the next call), or
  // null at the end of the stream. Fetches the GOP it needs and, once a frame of a GOP comes
  // out, the readAhead GOPs after it. Rejects with GopStreamError on an HTTP error (a GOP whose
  // request failed is not requested again: open a new streamer).
  async nextFrame() {
    for (;;) {
      if (this.closed) throw new GopStreamError('the streamer is closed');
      this.feed();
      const frame = this.decoder.nextFrame();
      if (frame) {
        if (this.target !== null && ((frame.frameIndex - this.target) | 0) < 0) continue;
        this.target = null;
        // Frames come in stream order: the GOP playing is found from the last one on.
        const playing = Math.max(this.playing, this.gopOf(frame.frameIndex, this.playing));
        this.playing = playing;
        for (let g = playing + 1; g <= playing + this.readAhead && g < this.gops.length; ++g) this.request(g);
        return frame;
      }
      if (this.ended) return null;
      if (this.cursor >= this.gops.length) {
        this.decoder.end();
        this.ended = true;
        continue;
      }
      const entry = this.request(this.cursor);
      if (entry.error) throw entry.error;
      await new Promise((wake) => entry.wakers.push(wake));
    }
  }

  // Pushes to the decoder the chunks that arrived, in stream order.
  feed() {
    while (this.cursor < this.gops.length) {
      const entry = this.entries.get(this.cursor);
      if (!entry) return;
      while (this.pushedChunks < entry.chunks.length) this.decoder.push(entry.chunks[this.pushedChunks++]);
      if (!entry.done) return;
      ++this.cursor;
      this.pushedChunks = 0;
    }
  }

  // The entry of GOP `g`, its request started if it was not.
  request(g) {
    let entry = this.entries.get(g);
    if (entry) return entry;
    entry = { chunks: [], received: 0, done: false, error: null, wakers: [] };
    this.entries.set(g, entry);
    const wake = () => {
      for (const w of entry.wakers.splice(0)) w();
    };
    this.fetchGop(g, entry, wake).catch((error) => {
      entry.error = error instanceof GopStreamError ? error : new GopStreamError(error.message);
      wake();
    });
    return entry;
  }

  // One Range request for GOP `g`; its body into entry.chunks as it arrives.
  async fetchGop(g, entry, wake) {
    const { offset, bytes } = this.gops[g];
    const start = offset;
    const end = offset + bytes - 1;
    this.requests.push({ gop: g, start, end });
    let response;
    try {
      response = await this.fetchFn(this.url, { headers: { Range: `bytes=${start}-${end}` } });
    } catch (error) {
      throw new GopStreamError(`cannot fetch ${this.url}: ${error.message}`);
    }
    if (response.status === 200) {
      await response.body?.cancel();
      throw new GopStreamError(`${this.url}: the server ignores range requests (HTTP 200, not 206)`);
    }
    if (response.status === 416) {
      throw new GopStreamError(`${this.url}: range ${start}-${end} not satisfiable: the GOP index does not match the stream`);
    }
    if (response.status !== 206) throw new GopStreamError(`${this.url}: HTTP ${response.status}`);
    const range = /^bytes (\d+)-(\d+)\/(\d+|\*)$/.exec(response.headers.get('content-range') ?? '');
    if (!range || Number(range[1]) !== start || Number(range[2]) !== end) {
      await response.body?.cancel();
      throw new GopStreamError(`${this.url}: the server sent ${response.headers.get('content-range')} for bytes ${start}-${end}`);
    }
    if (range[3] !== '*' && Number(range[3]) !== this.index.stream_bytes) {
      await response.body?.cancel();
      throw new GopStreamError(`${this.url} holds ${range[3]} bytes, the GOP index ${this.index.stream_bytes}: the index does not match the stream`);
    }
    const reader = response.body.getReader();
    for (;;) {
      const { done, value } = await reader.read();
      if (done) break;
      if (this.closed) {
        await reader.cancel();
        return;
      }
      entry.chunks.push(value);
      entry.received += value.length;
      this.bytesFetched += value.length;
      wake();
    }
    if (entry.received !== bytes) {
      throw new GopStreamError(`${this.url}: GOP ${g} ended after ${entry.received} of ${bytes} bytes`);
    }
    entry.done = true;
    wake();
  }

  // Releases the decoder; requests still running stop at their next chunk, and a pending
  // nextFrame() rejects.
  close() {
    if (this.closed) return;
    this.closed = true;
    this.decoder.close();
    for (const entry of this.entries.values()) {
      for (const wake of entry.wakers.splice(0)) wake();
    }
  }
}
