// AbrFrameSource (web/js/abr_frame_source.mjs) over a test double of AbrController: frames
// come out in order as SplatFrames tagged with their rendition, the first frame of each
// rendition carries its static layer even when it equals the previous one, fetching stops
// while maxFrames wait, a seek restarts at the random-access GOP and skips the frames before
// the target, and a fetch error reaches nextFrame(). No network, no decoder.
import assert from 'node:assert/strict';
import { test } from 'node:test';

import { AbrFrameSource } from '../js/abr_frame_source.mjs';
import { PlayerCore } from '../js/player_core.mjs';

const layer = (value) => ({
  count: 1, shDegree: 0, shCoefficients: 1, positions: new Float32Array([value, 0, 0]),
  logScales: new Float32Array(3), rotations: new Float32Array([1, 0, 0, 0]),
  opacityLogits: new Float32Array(1), sh: new Float32Array(3),
});

// GOPs of 2 frames; random-access at even GOPs; GOP g's rendition from `plan` (ids).
class FakeController {
  constructor(plan, { failAt = -1 } = {}) {
    this.plan = plan;
    this.failAt = failAt;
    this.options = { maxBufferSeconds: 2 };
    this.manifest = {
      fps: 2, frames: 2 * plan.length,
      renditions: [{ gops: plan.map((_, g) => ({ frame: 2 * g, frames: 2, random_access: g % 2 === 0 })) }],
    };
    this.nextGopIndex = 0;
    this.fetched = [];
    this.decoder = null;
  }
  get done() { return this.nextGopIndex >= this.plan.length; }
  get rendition() { return this.plan[Math.min(this.nextGopIndex, this.plan.length - 1)]; }
  get switchLog() { return []; }
  get stalls() { return { count: 0, ms: 0, list: [] }; }
  async nextGop() {
    const g = this.nextGopIndex++;
    await new Promise((resolve) => setTimeout(resolve, 1));
    if (g === this.failAt) throw new Error('m4d rendition: HTTP 500');
    this.fetched.push(g);
    for (const f of [2 * g, 2 * g + 1]) {
      // The same static layer in every rendition: only the switch makes it be sent again.
      this.options.onFrame({ frameIndex: f, isKeyframe: f % 2 === 0, layers: 2, concealedLayers: 0,
        static: layer(0), dynamic: layer(f) }, this.plan[g]);
    }
    return { gop: g };
  }
  seek(frame) {
    let g = 0;
    this.manifest.renditions[0].gops.forEach((gop, i) => { if (gop.random_access && gop.frame <= frame) g = i; });
    this.nextGopIndex = g;
    return 2 * g;
  }
  close() {}
}

test('frames in order; staticChanged at the start and at each switch; a seek skips to its target', async () => {
  const controller = new FakeController(['r1', 'r1', 'r5', 'r5', 'r1', 'r1']);
  const source = await AbrFrameSource.open(controller, { maxFrames: 4 });
  const frames = [];
  for (let f; (f = await source.nextFrame());) frames.push(f);
  assert.deepEqual(frames.map((f) => f.frameIndex), [...Array(12).keys()]);
  assert.deepEqual(frames.filter((f) => f.staticChanged).map((f) => `${f.frameIndex} ${f.rendition}`),
    ['0 r1', '4 r5', '8 r1']);
  assert.ok(frames.every((f) => f.staticChanged === (f.static !== null)));
  assert.equal(source.ended, true);
  assert.equal(source.streamInfo().fps, 2);

  // Frame 7 is in GOP 3, whose random-access point is GOP 2 (frame 4).
  assert.equal(await source.seek(7), true);
  const first = await source.nextFrame();
  assert.equal(first.frameIndex, 7);
  assert.equal(first.staticChanged, true);
  assert.deepEqual(controller.fetched.slice(-2), [2, 3]);
  assert.equal(await source.seek(99), false);
  await source.close();
});

test('fetching pauses while maxFrames wait; a fetch error reaches the player', async () => {
  const controller = new FakeController(['r1', 'r1', 'r1', 'r1'], { failAt: 3 });
  const source = await AbrFrameSource.open(controller, { maxFrames: 2 });
  await new Promise((resolve) => setTimeout(resolve, 30));
  assert.deepEqual(controller.fetched, [0]);  // 2 frames wait: no more fetches
  const core = new PlayerCore(source, { maxQueue: 8 });
  for (let i = 0; i < 200 && !core.error; ++i) await new Promise((resolve) => setTimeout(resolve, 2));
  assert.match(String(core.error), /HTTP 500/);
  assert.deepEqual(controller.fetched, [0, 1, 2]);
  await source.close();
});
