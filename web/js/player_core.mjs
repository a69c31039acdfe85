// player_core.mjs - the clock and frame pacing of an M4D player, apart from any rendering:
// play, pause, seek, and which frame to show at a given time. Frames come from any source with
// nextFrame() and seek() (M4dWorkerDecoder, or a test double); the render loop calls tick().
//
//   const core = new PlayerCore(decoder);         // { fps, maxQueue, maxLagMs }
//   core.play();
//   requestAnimationFrame(function loop(now) {
//     const frame = core.tick(now);               // a SplatFrame to show, or null: keep the last
//     if (frame) adapter.update(frame);
//     requestAnimationFrame(loop);
//   });
//
// The clock runs at the stream's fps from the first frame shown. Frames are requested ahead
// (up to maxQueue waiting); at each tick the newest frame due is shown and the due frames it
// overtakes are dropped (stats.dropped): that happens when decoding fell behind the clock (a
// slow keyframe) and then caught up. A dropped frame's new static layer moves on to the frame
// shown, so a viewer never misses one. When the source has no bytes for the next frame due
// (nextFrame() resolved null), the clock stops until a frame comes (stats.stalls). Decoding
// cannot skip frames (an inter frame needs the one before), so if decoding stays slower than
// the stream, frames are shown late and the clock is moved back once the frame shown lags it by
// more than maxLagMs (stats.resyncs).

// The clock and pacing of a player over a frame source.
export class PlayerCore {
  // source: { nextFrame(): Promise<SplatFrame | null>, seek(frame): Promise<boolean>,
  // streamInfo?(): { fps } | null, ended?: boolean }. options.fps overrides the stream's
  // (default: the source's streamInfo().fps, else 30); options.maxQueue: frames decoded ahead
  // (default 3); options.maxLagMs: the lag after which the clock is moved back (default 1000).
  constructor(source, options = {}) {
    if (!source || typeof source.nextFrame !== 'function' || typeof source.seek !== 'function') {
      throw new TypeError('PlayerCore: the source needs nextFrame() and seek()');
    }
    this.source = source;
    this.options = { maxQueue: 3, maxLagMs: 1000, ...options };
    this.playing = false;
    /** The frame shown last (a SplatFrame), or null. */
    this.current = null;
    /** The error the source threw, if any; the player then stops requesting frames. */
    this.error = null;
    /** shown: frames returned by tick(); dropped: due frames overtaken; stalls: waits for bytes;
     * resyncs: clock moved back after a lag. */
    this.stats = { shown: 0, dropped: 0, stalls: 0, resyncs: 0 };
    this.queue = [];
    this.pending = null;
    this.origin = null;       // { ms, frame, fps }: the clock, set when a frame is first due
    this.needsFrame = true;   // show the next frame even when paused (the start, after a seek)
    this.sourceEnded = false;
    this.starved = false;     // the source had no frame: more bytes needed
    this.stalled = false;
    this.seeking = 0;
    this.seeks = Promise.resolve();
    this.generation = 0;
    this.pump();
  }

  /** Frames per second of the clock: options.fps, else the stream's, else 30. */
  get fps() {
    const info = typeof this.source.streamInfo === 'function' ? this.source.streamInfo() : null;
    return this.options.fps || (info && info.fps) || 30;
  }

  /** True when the source is over and every frame was shown or dropped. */
  get ended() {
    return this.sourceEnded && this.queue.length === 0 && !this.pending;
  }

  // Starts (or resumes) the clock from the next frame.
  play() {
    this.playing = true;
    this.origin = null;
  }

  // Stops the clock; the frame shown stays.
  pause() {
    this.playing = false;
    this.origin = null;
  }

  // Paused: the next tick shows the next frame (one step forward, no seek); playing: nothing.
  step() {
    if (!this.playing) this.needsFrame = true;
  }

  // Goes to `frame` (the source restarts at its random-access point); the next tick shows it,
  // playing or paused. Resolves false (nothing changed) when the source does not have it yet.
  seek(frame) {
    const run = async () => {
      ++this.seeking;
      try {
        if (this.pending) await this.pending;
        const done = await this.source.seek(frame);
        if (done) {
          ++this.generation;
          this.queue = [];
          this.sourceEnded = false;
          this.starved = false;
          this.origin = null;
          this.needsFrame = true;
        }
        return done;
      } finally {
        --this.seeking;
        this.pump();
      }
    };
    const result = this.seeks.then(run, run);
    this.seeks = result.catch(() => {});
    return result;
  }

  // The frame to show at time nowMs (milliseconds, e.g. requestAnimationFrame's), or null to
  // keep showing the current one.
  tick(nowMs) {
    this.pump();
    if (this.error) return null;
    const shownIndex = this.current ? this.current.frameIndex : -Infinity;
    if (this.queue.length === 0) {
      if (this.playing && this.origin && this.starved && !this.sourceEnded && this.target(nowMs) > shownIndex) {
        this.origin = null;  // waiting for bytes: the clock stops
        if (!this.stalled) ++this.stats.stalls;
        this.stalled = true;
      }
      return null;
    }
    let target;
    if (!this.playing) {
      if (!this.needsFrame) return null;
      target = this.queue[0].frameIndex;
    } else {
      if (!this.origin) this.origin = { ms: nowMs, frame: this.queue[0].frameIndex, fps: this.fps };
      target = this.target(nowMs);
    }
    let show = null;
    while (this.queue.length && this.queue[0].frameIndex <= target) {
      const next = this.queue.shift();
      if (show) {
        ++this.stats.dropped;
        if (show.staticChanged && !next.staticChanged) {
          next.staticChanged = true;
          next.static = show.static;
        }
      }
      show = next;
    }
    this.pump();
    if (!show) return null;
    if (this.playing && (target - show.frameIndex) * 1000 / this.origin.fps > this.options.maxLagMs) {
      this.origin = { ms: nowMs, frame: show.frameIndex, fps: this.origin.fps };
      ++this.stats.resyncs;
    }
    this.current = show;
    this.needsFrame = false;
    this.stalled = false;
    ++this.stats.shown;
    return show;
  }

  target(nowMs) {
    return this.origin.frame + Math.floor(((nowMs - this.origin.ms) * this.origin.fps) / 1000 + 1e-9);
  }

  pump() {
    if (this.pending || this.seeking || this.error || this.sourceEnded || this.queue.length >= this.options.maxQueue) return;
    const generation = this.generation;
    this.pending = Promise.resolve()
      .then(() => this.source.nextFrame())
      .then((frame) => {
        this.pending = null;
        if (generation !== this.generation) return;
        if (frame) {
          this.queue.push(frame);
          this.starved = false;
          this.pump();
        } else if (this.source.ended) {
          this.sourceEnded = true;
        } else {
          this.starved = true;  // asked again at the next tick
        }
      }, (error) => {
        this.pending = null;
        this.error = error instanceof Error ? error : new Error(String(error));
      });
  }
}
