// Tests of the player core (web/js/player_core.mjs) in Node.js against a test double of a frame
// source: pacing by the stream's fps, pause, seek, frames dropped when decoding falls behind,
// stalls while bytes are missing. Time is given to tick(), never read: nothing here is timed.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { PlayerCore } from '../js/player_core.mjs';

const flush = async () => {
  for (let i = 0; i < 10; ++i) await new Promise((done) => setImmediate(done));
};

// A source of `count` frames at `fps`, keyframes (static layer changed) every `gop` frames.
// manual: each nextFrame() waits for release(); available: frames whose bytes have arrived
// (nextFrame() resolves null past them, as a decoder waiting for bytes does).
class FakeSource {
  constructor(count, { fps = 10, gop = 4, manual = false, available = count } = {}) {
    Object.assign(this, { count, fps, gop, manual, available });
    this.position = 0;
    this.sendStatic = true;
    this.ended = false;
    this.waiters = [];
    this.requests = 0;
    this.seeks = [];
  }

  streamInfo() {
    return { fps: this.fps };
  }

  produce() {
    if (this.position >= this.available) {
      this.ended = this.available === this.count;
      return null;
    }
    const frameIndex = this.position++;
    const isKeyframe = frameIndex % this.gop === 0;
    const staticChanged = this.sendStatic || isKeyframe;
    this.sendStatic = false;
    return { frameIndex, isKeyframe, staticChanged, static: staticChanged ? { from: frameIndex } : null, dynamic: { frameIndex } };
  }

  nextFrame() {
    ++this.requests;
    if (!this.manual) return Promise.resolve(this.produce());
    return new Promise((resolve) => this.waiters.push(resolve));
  }

  // Lets `n` waiting requests complete (the player asks again after each).
  async release(n) {
    for (let i = 0; i < n; ++i) {
      await flush();
      assert.ok(this.waiters.length > 0, 'the player has a request waiting');
      this.waiters.shift()(this.produce());
    }
    await flush();
  }

  async seek(frame) {
    this.seeks.push(frame);
    if (frame >= this.available) return false;
    this.position = frame;
    this.sendStatic = true;
    this.ended = false;
    return true;
  }
}

const index = (frame) => (frame ? frame.frameIndex : null);

test('paces frames by the stream fps from the first frame shown', async () => {
  const core = new PlayerCore(new FakeSource(10, { fps: 10 }));
  assert.equal(core.fps, 10);
  core.play();
  await flush();
  assert.equal(index(core.tick(1000)), 0);
  assert.equal(index(core.tick(1050)), null);
  assert.equal(index(core.tick(1099)), null);
  await flush();
  assert.equal(index(core.tick(1100)), 1);
  assert.equal(index(core.tick(1199)), null);
  await flush();
  assert.equal(index(core.tick(1200)), 2);
  assert.deepEqual(core.stats, { shown: 3, dropped: 0, stalls: 0, resyncs: 0 });
  // Decodes ahead, but no more than maxQueue frames.
  await flush();
  assert.ok(core.queue.length <= 3);
});

test('shows the first frame while paused, then holds until play; resumes where it stopped', async () => {
  const source = new FakeSource(10);
  const core = new PlayerCore(source);
  await flush();
  assert.equal(index(core.tick(0)), 0);
  assert.equal(index(core.tick(5000)), null);
  core.play();
  await flush();
  assert.equal(index(core.tick(6000)), 1);
  await flush();
  assert.equal(index(core.tick(6100)), 2);
  core.pause();
  await flush();
  assert.equal(index(core.tick(9000)), null);
  assert.equal(core.current.frameIndex, 2);
  core.play();
  await flush();
  assert.equal(index(core.tick(9500)), 3);
  await flush();
  assert.equal(index(core.tick(9600)), 4);
  assert.equal(core.stats.dropped, 0);
});

test('step() shows the next frame while paused, once, without a seek', async () => {
  const source = new FakeSource(10);
  const core = new PlayerCore(source);
  await flush();
  assert.equal(index(core.tick(0)), 0);
  core.step();
  assert.equal(index(core.tick(10)), 1);
  assert.equal(index(core.tick(5000)), null);  // one step only
  await flush();
  core.step();
  const third = core.tick(5001);
  assert.equal(index(third), 2);
  assert.equal(third.staticChanged, false);
  assert.deepEqual(source.seeks, []);
  assert.equal(core.stats.dropped, 0);
});

test('seeks, playing or paused, and the frame sought brings its static layer', async () => {
  const source = new FakeSource(12, { available: 10 });
  const core = new PlayerCore(source);
  core.play();
  await flush();
  assert.equal(index(core.tick(0)), 0);
  assert.equal(await core.seek(7), true);
  await flush();
  const sought = core.tick(10);
  assert.equal(index(sought), 7);
  assert.equal(sought.staticChanged, true);
  await flush();
  assert.equal(index(core.tick(110)), 8);
  core.pause();
  assert.equal(await core.seek(2), true);
  await flush();
  assert.equal(index(core.tick(5000)), 2);
  assert.equal(index(core.tick(6000)), null);
  // A frame whose bytes have not arrived: nothing changes.
  assert.equal(await core.seek(11), false);
  assert.deepEqual(source.seeks, [7, 2, 11]);
  core.play();
  await flush();
  assert.equal(index(core.tick(7000)), 3);
  assert.equal(core.stats.dropped, 0);
});

test('drops the due frames overtaken when decoding falls behind, keeping new static layers', async () => {
  const source = new FakeSource(12, { manual: true, gop: 3 });
  const core = new PlayerCore(source);
  core.play();
  await source.release(1);
  assert.equal(index(core.tick(0)), 0);
  // Decoding stalls for three frame times: nothing to show, the clock runs on.
  for (const t of [100, 200, 300]) assert.equal(core.tick(t), null);
  assert.equal(core.stats.stalls, 0);
  // Frames 1-3 arrive at once: 3 is due, 1 and 2 are dropped; frame 3 is a keyframe.
  await source.release(3);
  const shown = core.tick(300);
  assert.equal(index(shown), 3);
  assert.equal(core.stats.dropped, 2);
  // Again, over a keyframe that is dropped (6): its static layer comes with frame 7.
  await source.release(3);  // 4, 5, 6
  assert.equal(index(core.tick(400)), 4);
  await source.release(1);  // 7
  const caught = core.tick(700);
  assert.equal(index(caught), 7);
  assert.equal(caught.staticChanged, true);
  assert.deepEqual(caught.static, { from: 6 });
  assert.equal(core.stats.dropped, 4);
});

test('stops the clock while bytes are missing (a stall) and resumes without drops', async () => {
  const source = new FakeSource(8, { available: 3 });
  const core = new PlayerCore(source);
  core.play();
  await flush();
  for (const [t, frame] of [[0, 0], [100, 1], [200, 2]]) {
    await flush();
    assert.equal(index(core.tick(t)), frame);
  }
  await flush();
  assert.equal(core.tick(300), null);
  assert.equal(core.tick(900), null);
  assert.equal(core.stats.stalls, 1);
  source.available = 8;
  await flush();
  let resumed = core.tick(1000);  // asks again, if it had not since
  if (!resumed) {
    await flush();
    resumed = core.tick(1000);
  }
  assert.equal(index(resumed), 3);
  await flush();
  assert.equal(index(core.tick(1100)), 4);
  assert.equal(core.stats.dropped, 0);
  assert.equal(core.stats.stalls, 1);
  for (let t = 1200; !core.ended && t < 3000; t += 100) {
    await flush();
    core.tick(t);
  }
  assert.equal(core.current.frameIndex, 7);
  assert.equal(core.ended, true);
});

test('keeps the lag bounded when decoding stays slower than the stream', async () => {
  const source = new FakeSource(40, { manual: true });
  const core = new PlayerCore(source, { maxLagMs: 500 });
  core.play();
  await source.release(1);
  assert.equal(index(core.tick(0)), 0);
  // One frame decoded every 200 ms at 10 fps.
  for (let k = 1; k <= 10; ++k) {
    await source.release(1);
    assert.equal(index(core.tick(200 * k)), k);
  }
  assert.ok(core.stats.resyncs >= 1);
  assert.equal(core.stats.dropped, 0);
});

test('a source that throws stops the player with its error', async () => {
  const core = new PlayerCore({ nextFrame: async () => { throw new Error('worker died'); }, seek: async () => false });
  core.play();
  await flush();
  assert.equal(core.tick(0), null);
  assert.match(core.error.message, /worker died/);
  assert.throws(() => new PlayerCore({}), /nextFrame/);
});
