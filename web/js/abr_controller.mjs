// abr_controller.mjs - adaptive bitrate over the renditions of `m4d encode --renditions`.
//
//   import { loadM4d } from './m4d.mjs';
//   import { AbrController } from './abr_controller.mjs';
//   const m4d = await loadM4d();
//   const abr = new AbrController({ manifestUrl: 'show.manifest.json',
//                                   openDecoder: () => m4d.openDecoder(),
//                                   onFrame: (frame, rendition) => draw(frame) });
//   await abr.load();
//   while (await abr.nextGop()) {}      // or: await abr.run();
//   abr.switchLog; abr.stalls;          // what happened
//
// The manifest (OUT.manifest.json) lists renditions with aligned GOPs. The controller fetches
// one GOP at a time with an HTTP Range request, measures the throughput of that fetch (bytes
// over the time it took), and chooses the next GOP's rendition from the smoothed throughput
// or the last fetch's when lower: down as soon as it times a safety factor falls below the
// current rendition's bandwidth, up when it exceeds a higher rendition's with a margin. It switches
// only where the next GOP is a random-access point in the manifest, with a new decoder.
//
// Playback is modelled on the wall clock, as a player would show the frames: playback starts
// when the first GOP is decoded; a GOP that arrives after its frames were due is a stall (the
// clock waits for it); the controller fetches at most maxBufferSeconds of content ahead.

// The manifest checked: a clear Error for anything that is not one (format, version,
// renditions sorted by bandwidth with aligned GOPs). Returns the manifest.
export function validateManifest(manifest) {
  const fail = (what) => {
    throw new Error(`m4d manifest: ${what}`);
  };
  if (!manifest || typeof manifest !== 'object') fail('not a JSON object');
  if (manifest.format !== 'm4d-manifest') fail(`format "${manifest.format}" is not "m4d-manifest"`);
  if (manifest.version !== 1) fail(`version ${manifest.version} is not 1`);
  if (!(manifest.fps > 0) || !(manifest.frames > 0)) fail('no fps or frames');
  const renditions = manifest.renditions;
  if (!Array.isArray(renditions) || renditions.length === 0) fail('no rendition');
  for (const [i, r] of renditions.entries()) {
    if (typeof r.id !== 'string' || typeof r.url !== 'string') fail(`rendition ${i}: no id or url`);
    if (!(r.bandwidth > 0) || !Array.isArray(r.gops) || r.gops.length === 0) {
      fail(`rendition ${r.id}: no bandwidth or GOPs`);
    }
    if (i > 0 && r.bandwidth < renditions[i - 1].bandwidth) fail('renditions not sorted by bandwidth');
    if (r.gops.length !== renditions[0].gops.length) fail(`rendition ${r.id}: GOPs not aligned`);
    for (const [g, gop] of r.gops.entries()) {
      const first = renditions[0].gops[g];
      if (gop.frame !== first.frame || gop.frames !== first.frames ||
          gop.random_access !== first.random_access) {
        fail(`rendition ${r.id}: GOP ${g} not aligned with rendition ${renditions[0].id}'s`);
      }
      if (!(gop.bytes > 0) || !(gop.offset >= 0)) fail(`rendition ${r.id}: GOP ${g} has no bytes`);
    }
  }
  if (!renditions[0].gops[0].random_access) fail('the first GOP is not a random-access point');
  return manifest;
}

// The rendition (index into renditions, sorted by bandwidth ascending) for the next GOP from
// a throughput estimate (bits per second): down to the highest whose bandwidth is at most
// safety * estimate when the current one is above that; up to the highest whose bandwidth
// times upMargin is at most the estimate (upMargin > 1 / safety leaves a band where neither
// happens, so that the choice does not flap); otherwise the current one.
export function chooseRendition(renditions, current, estimate, { safety = 0.75, upMargin = 1.5 } = {}) {
  const highestUnder = (limit) => {
    let best = 0;
    renditions.forEach((r, i) => {
      if (r.bandwidth <= limit) best = i;
    });
    return best;
  };
  if (renditions[current].bandwidth > safety * estimate) {
    return Math.min(current, highestUnder(safety * estimate));
  }
  const up = highestUnder(estimate / upMargin);
  return up > current ? up : current;
}

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

// Plays a manifest's renditions GOP by GOP, switching rendition from the measured throughput.
export class AbrController {
  // options: manifestUrl (required); openDecoder() -> a new M4dDecoder (required);
  // onFrame(frame, renditionId) for every decoded frame (valid during the call); fetch
  // (default globalThis.fetch); safety (0.75), upMargin (1.5), smoothing (0.5: the weight of
  // a new measure in the smoothed estimate); maxBufferSeconds (2) of content fetched ahead;
  // start: the first rendition's id (default the lowest).
  constructor(options) {
    if (!options || !options.manifestUrl || typeof options.openDecoder !== 'function') {
      throw new TypeError('AbrController: manifestUrl and openDecoder are required');
    }
    this.options = { safety: 0.75, upMargin: 1.5, smoothing: 0.5, maxBufferSeconds: 2, ...options };
    this.fetch = options.fetch || globalThis.fetch.bind(globalThis);
    this.manifest = null;
    this.renditions = [];
    this.nextGopIndex = 0;
    this.current = 0;
    this.decoder = null;
    this.decoderRendition = -1;
    this.estimate = 0;  // smoothed throughput, bits per second (0: none measured yet)
    this.lastThroughput = 0;
    this.log = [];
    this.stallList = [];
    this.stalledMs = 0;
    this.startTime = 0;  // when the first fetch began
    this.playStart = -1;  // wall-clock ms when frame 0 of the content showed
    this.bytesFetched = 0;
  }

  // Fetches and checks the manifest; returns it.
  async load() {
    const response = await this.fetch(this.options.manifestUrl);
    if (!response.ok) {
      throw new Error(`m4d manifest: ${this.options.manifestUrl}: HTTP ${response.status}`);
    }
    let json;
    try {
      json = await response.json();
    } catch (e) {
      throw new Error(`m4d manifest: ${this.options.manifestUrl}: not JSON (${e.message})`);
    }
    this.manifest = validateManifest(json);
    this.renditions = this.manifest.renditions.map((r) => ({
      ...r, href: new URL(r.url, new URL(this.options.manifestUrl, globalThis.location?.href ?? 'file:///')).href,
    }));
    if (this.options.start !== undefined) {
      this.current = this.renditions.findIndex((r) => r.id === this.options.start);
      if (this.current < 0) throw new RangeError(`AbrController: no rendition ${this.options.start}`);
    }
    return this.manifest;
  }

  // The id of the rendition the next GOP comes from.
  get rendition() {
    return this.renditions[this.current].id;
  }

  // The smoothed throughput estimate, bits per second (0 before the first fetch).
  get throughput() {
    return this.estimate;
  }

  // What decisions use: the smoothed throughput, or the last fetch's when lower (down at
  // once when the throughput falls, up only once it held for more than one fetch).
  decisionEstimate() {
    return Math.min(this.lastThroughput, this.estimate);
  }

  // Every switch: { frame (first frame of the new rendition), from, to, throughput (the
  // estimate it was decided on, bits per second), time (ms since the first fetch) }.
  get switchLog() {
    return this.log.slice();
  }

  // Stalls: { count, ms (total), list: [{ frame, ms }] }.
  get stalls() {
    return { count: this.stallList.length, ms: this.stalledMs, list: this.stallList.slice() };
  }

  // Whether every GOP was played.
  get done() {
    return this.manifest !== null && this.nextGopIndex >= this.manifest.renditions[0].gops.length;
  }

  // Fetches, decodes and plays the next GOP. Returns { gop, frame, frames, rendition, bytes,
  // seconds, throughput (of this fetch), stallMs, switched, decodedFrames }, or null at the end.
  async nextGop() {
    if (!this.manifest) throw new Error('AbrController: load() first');
    if (this.done) return null;
    const g = this.nextGopIndex;
    const fps = this.manifest.fps;
    const firstFrame = this.renditions[0].gops[0].frame;
    const gopInfo = this.renditions[0].gops[g];
    const contentMs = ((gopInfo.frame - firstFrame) / fps) * 1000;
    // Keep at most maxBufferSeconds of content ahead of the playhead.
    if (this.playStart >= 0) {
      const dueAt = this.playStart + this.stalledMs + contentMs;
      const ahead = dueAt - performance.now();
      const limit = this.options.maxBufferSeconds * 1000;
      if (ahead > limit) await sleep(ahead - limit);
    }
    // Rendition: switch only where this GOP is a random-access point.
    let switched = false;
    if (g > 0 && gopInfo.random_access && this.estimate > 0) {
      const next = chooseRendition(this.renditions, this.current, this.decisionEstimate(),
        this.options);
      if (next !== this.current) {
        this.log.push({
          frame: gopInfo.frame, from: this.renditions[this.current].id, to: this.renditions[next].id,
          throughput: this.decisionEstimate(), time: performance.now() - this.startTime,
        });
        this.current = next;
        switched = true;
      }
    }
    const rendition = this.renditions[this.current];
    const gop = rendition.gops[g];
    const start = performance.now();
    if (g === 0) this.startTime = start;
    const bytes = await this.fetchRange(rendition.href, gop.offset, gop.bytes);
    const seconds = Math.max((performance.now() - start) / 1000, 1e-6);
    const measured = (8 * bytes.length) / seconds;
    const a = this.options.smoothing;
    this.estimate = this.estimate > 0 ? a * measured + (1 - a) * this.estimate : measured;
    this.lastThroughput = measured;
    this.bytesFetched += bytes.length;

    // Decode: a new decoder when the rendition changes (always at a random-access point).
    if (this.decoderRendition !== this.current) {
      if (this.decoder) this.decoder.close();
      this.decoder = this.options.openDecoder();
      this.decoderRendition = this.current;
    }
    this.decoder.push(bytes);
    if (g + 1 === rendition.gops.length) this.decoder.end();
    let decodedFrames = 0;
    for (let f; (f = this.decoder.nextFrame()); ++decodedFrames) {
      if (this.options.onFrame) this.options.onFrame(f, rendition.id);
    }

    // Playback: the first GOP starts the clock; a later one that arrives late is a stall.
    const now = performance.now();
    let stallMs = 0;
    if (this.playStart < 0) {
      this.playStart = now - contentMs - this.stalledMs;  // stalledMs: 0 but after a seek
    } else {
      const dueAt = this.playStart + this.stalledMs + contentMs;
      if (now > dueAt) {
        stallMs = now - dueAt;
        this.stalledMs += stallMs;
        this.stallList.push({ frame: gop.frame, ms: stallMs });
      }
    }
    this.nextGopIndex = g + 1;
    return {
      gop: g, frame: gop.frame, frames: gop.frames, rendition: rendition.id, bytes: bytes.length,
      seconds, throughput: measured, stallMs, switched, decodedFrames,
    };
  }

  // Plays every remaining GOP; returns the switch log.
  async run() {
    while (await this.nextGop()) { /* each GOP in turn */ }
    return this.switchLog;
  }

  // Bytes [offset, offset + length) of url by an HTTP Range request (a server that answers
  // 200 with the whole file is sliced).
  async fetchRange(url, offset, length) {
    const response = await this.fetch(url, {
      headers: { Range: `bytes=${offset}-${offset + length - 1}` },
    });
    if (response.status !== 206 && response.status !== 200) {
      throw new Error(`m4d rendition: ${url}: HTTP ${response.status}`);
    }
    let bytes = new Uint8Array(await response.arrayBuffer());
    if (response.status === 200) bytes = bytes.subarray(offset, offset + length);
    if (bytes.length !== length) {
      throw new Error(`m4d rendition: ${url}: ${bytes.length} bytes at ${offset}, not ${length}`);
    }
    return bytes;
  }

  // Restarts at the random-access GOP at or before `frame` (with a new decoder; playback
  // timing starts again from it). Returns the first frame of that GOP. Not while nextGop() runs.
  seek(frame) {
    if (!this.manifest) throw new Error('AbrController: load() first');
    const gops = this.renditions[0].gops;
    let g = 0;
    gops.forEach((gop, i) => {
      if (gop.random_access && gop.frame <= frame) g = i;
    });
    this.close();
    this.nextGopIndex = g;
    this.playStart = -1;
    return gops[g].frame;
  }

  // Closes the decoder.
  close() {
    if (this.decoder) this.decoder.close();
    this.decoder = null;
    this.decoderRendition = -1;
  }
}
