// Compiled by tsc --noEmit (scripts/test_web.sh): the m4d-player package's core (README's
// example), typed against worker_decoder.d.mts, player_core.d.mts and splat_frame.d.mts.
import { M4dWorkerDecoder, PlayerCore, linearScales, opacities, type SplatFrame } from '../js/index.mjs';
import { normalisedRotationsXyzw, rgbFromShDc, transferablesOf, type SplatLayer } from '../js/splat_frame.mjs';
import type { FrameSource } from '../js/player_core.mjs';

export async function play(url: string, draw: (layer: SplatLayer, scales: Float32Array) => void): Promise<number> {
  const decoder = new M4dWorkerDecoder({ layers: 'all', maxGaussians: 1 << 20 });
  const { version } = await decoder.open();
  await decoder.push(new Uint8Array(await (await fetch(url)).arrayBuffer()));
  await decoder.end();
  const source: FrameSource = decoder;
  const core = new PlayerCore(source, { maxQueue: 2 });
  core.play();
  let background: SplatLayer | null = null;
  const frame: SplatFrame | null = core.tick(performance.now());
  if (frame) {
    if (frame.staticChanged && frame.static) background = frame.static;
    draw(frame.dynamic, linearScales(frame.dynamic));
    const alpha: Float32Array = opacities(frame.dynamic);
    const xyzw: Float32Array = normalisedRotationsXyzw(frame.dynamic, new Float32Array(4 * frame.dynamic.count));
    const rgb: Float32Array = rgbFromShDc(frame.dynamic);
    const buffers: ArrayBuffer[] = transferablesOf(frame);
    if (alpha.length + xyzw.length + rgb.length + buffers.length < 0) throw new Error(version);
  }
  await core.seek(0);
  const info = decoder.streamInfo();
  decoder.close();
  return core.stats.dropped + core.stats.shown + (info ? info.fps : 0) + (background ? background.count : 0);
}
