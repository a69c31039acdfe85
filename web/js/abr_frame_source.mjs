// abr_frame_source.mjs - adaptive bitrate as a frame source of PlayerCore (player_core.mjs):
// an AbrController (abr_controller.mjs) fetches GOPs ahead in the background, choosing each
// GOP's rendition from the measured throughput; its frames come out as SplatFrames in order.
//
//   const abr = new AbrController({ manifestUrl, openDecoder: () => m4d.openDecoder() });
//   const source = await AbrFrameSource.open(abr);
//   const core = new PlayerCore(source);           // then core.tick(now) -> adapter.update()
//   source.rendition; source.switchLog; source.stalls;
//
// A switch happens only at a random-access GOP, with a new decoder: the first SplatFrame of the
// new rendition has staticChanged true (its static layer is that rendition's), whatever the
// static layers compare to.
import { SplatFrameMaker } from './splat_frame.mjs';

// A PlayerCore frame source over an AbrController.
export class AbrFrameSource {
  // controller: an AbrController (its onFrame option is replaced); options.maxFrames: decoded
  // frames kept ahead (default: the controller's maxBufferSeconds of frames, at least a GOP).
  constructor(controller, options = {}) {
    if (!controller || typeof controller.nextGop !== 'function') {
      throw new TypeError('AbrFrameSource: an AbrController is required');
    }
    this.controller = controller;
    this.options = { ...options };
    this.maker = new SplatFrameMaker();
    this.queue = [];
    /** True once every GOP was fetched and every frame taken. */
    this.ended = false;
    /** Milliseconds the last nextFrame() waited for a frame. */
    this.lastDecodeMs = 0;
    /** The rendition of the frame last taken by nextFrame(), or null. */
    this.shownRendition = null;
    /** The error the background fetching met, if any (nextFrame() then throws it). */
    this.error = null;
    this.skipBefore = -1;
    this.lastRendition = null;
    this.waiting = [];
    this.loop = null;
    this.running = false;
    this.stopping = false;
    controller.options.onFrame = (frame, rendition) => this.onFrame(frame, rendition);
  }

  // Loads the controller's manifest (unless loaded) and returns a started source.
  static async open(controller, options) {
    if (!controller.manifest) await controller.load();
    const source = new AbrFrameSource(controller, options);
    source.start();
    return source;
  }

  /** Decoded frames kept ahead before fetching pauses. */
  get maxFrames() {
    const m = this.controller.manifest;
    const gop = Math.max(...m.renditions[0].gops.map((g) => g.frames));
    return this.options.maxFrames ?? Math.max(gop, Math.ceil(this.controller.options.maxBufferSeconds * m.fps));
  }

  /** The rendition the next GOP comes from. */
  get rendition() {
    return this.controller.rendition;
  }

  /** The controller's switch log (AbrSwitch[]). */
  get switchLog() {
    return this.controller.switchLog;
  }

  /** The controller's stalls (GOPs that arrived after their frames were due). */
  get stalls() {
    return this.controller.stalls;
  }

  onFrame(frame, rendition) {
    if (rendition !== this.lastRendition) {
      this.maker.reset();
      this.lastRendition = rendition;
    }
    if (frame.frameIndex < this.skipBefore) return;
    const splat = this.maker.make(frame);
    splat.rendition = rendition;
    this.queue.push(splat);
  }

  notify() {
    const waiting = this.waiting;
    this.waiting = [];
    for (const wake of waiting) wake();
  }

  waitChange() {
    return new Promise((resolve) => { this.waiting.push(resolve); });
  }

  // Fetches GOPs in the background while fewer than maxFrames frames wait.
  start() {
    this.stopping = false;
    this.running = true;
    this.loop = (async () => {
      try {
        while (!this.stopping && !this.controller.done) {
          if (this.queue.length >= this.maxFrames) {
            await this.waitChange();
            continue;
          }
          await this.controller.nextGop();
          this.notify();
        }
      } catch (error) {
        this.error = error instanceof Error ? error : new Error(String(error));
      } finally {
        this.running = false;
        this.notify();
      }
    })();
  }

  // The next SplatFrame (with its `rendition`), or null at the end.
  async nextFrame() {
    const start = performance.now();
    while (this.queue.length === 0) {
      if (this.error) throw this.error;
      if (!this.running && this.controller.done) {
        this.ended = true;
        return null;
      }
      await this.waitChange();
    }
    const frame = this.queue.shift();
    this.shownRendition = frame.rendition;
    this.notify();
    this.lastDecodeMs = performance.now() - start;
    return frame;
  }

  // Restarts at the random-access GOP at or before `frame` (frames before `frame` are
  // skipped); the next SplatFrame carries the static layer. Resolves false when out of range.
  async seek(frame) {
    const m = this.controller.manifest;
    const gops = m.renditions[0].gops;
    const last = gops[gops.length - 1];
    if (!(frame >= gops[0].frame && frame < last.frame + last.frames)) return false;
    this.stopping = true;
    this.notify();
    await this.loop;
    this.controller.seek(frame);
    this.queue = [];
    this.maker.reset();
    this.skipBefore = frame;
    this.ended = false;
    this.error = null;
    this.start();
    return true;
  }

  // The stream's M4dStreamInfo (the current decoder's) or, before one, { fps } of the manifest.
  streamInfo() {
    const decoder = this.controller.decoder;
    const info = decoder && typeof decoder.streamInfo === 'function' ? decoder.streamInfo() : null;
    return info || (this.controller.manifest ? { fps: this.controller.manifest.fps } : null);
  }

  // Stops fetching and closes the controller's decoder.
  async close() {
    this.stopping = true;
    this.notify();
    await this.loop;
    this.controller.close();
  }
}
