// Compiled by tsc --noEmit (scripts/test_web.sh): a use of the PlayCanvas adapter typed against
// playcanvas_adapter.d.mts (PlayCanvas typed structurally there).
import { loadM4d } from '../js/m4d.mjs';
import { SplatFrameMaker } from '../js/splat_frame.mjs';
import {
  M4dPlayCanvasAdapter, setCaptureCamera, type PlayCanvasApp, type PlayCanvasEntity,
  type PlayCanvasModule, type SplatFrame,
} from '../adapters/playcanvas_adapter.mjs';

export async function playInto(pc: PlayCanvasModule, app: PlayCanvasApp, camera: PlayCanvasEntity, bytes: Uint8Array): Promise<number> {
  const m4d = await loadM4d();
  const decoder = m4d.openDecoder();
  decoder.push(bytes);
  decoder.end();
  const adapter = new M4dPlayCanvasAdapter(app, pc, { shDegree: 3 });
  setCaptureCamera(pc, camera, { fx: 300, fy: 300, cx: 160, cy: 120, rotation: [1, 0, 0, 0, 1, 0, 0, 0, 1], translation: [0, 0, 4] }, 320, 240);
  let ms = 0;
  const maker = new SplatFrameMaker();
  for (let f; (f = decoder.nextFrame());) {
    const frame: SplatFrame = maker.make(f);
    ms += adapter.update(frame);
  }
  const built: number = adapter.stats.staticBuilds + adapter.stats.dynamicBuilds;
  adapter.destroy();
  return built + ms;
}
