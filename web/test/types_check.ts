// Compiled by tsc --noEmit (scripts/test_web.sh): the embedding example of the README, typed
// against m4d.d.ts, so that the declarations stay usable and match the API's shape.
import { loadM4d, type M4dCamera, type M4dFrame } from '../js/m4d.mjs';

export async function play(canvas: HTMLCanvasElement, url: string): Promise<number> {
  const m4d = await loadM4d();
  const decoder = m4d.openDecoder({ layers: 'all', maxGaussians: 1 << 20 });
  const renderer = m4d.openRenderer(canvas, { background: [0, 0, 0], shDegree: 1 });
  const camera: M4dCamera = { fx: 800, fy: 800, cx: 480, cy: 270, rotation: [1, 0, 0, 0, 1, 0, 0, 0, 1], translation: [0, 0, 4] };
  decoder.push(new Uint8Array(await (await fetch(url)).arrayBuffer()));
  decoder.end();
  let frames = 0;
  for (let f: M4dFrame | null; (f = decoder.nextFrame()); ++frames) {
    const positions: Float32Array = f.dynamic.positions;
    if (positions.length !== 3 * f.dynamic.count) throw new Error(f.hash());
    renderer.upload(decoder, 'dynamic');
    renderer.draw(camera);
  }
  const info = decoder.streamInfo();
  if (decoder.errors.count > 0 || !info) throw new Error(decoder.errors.lastMessage);
  decoder.close();
  renderer.close();
  return frames + info.gops - renderer.stats().visible;
}
