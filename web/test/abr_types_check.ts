// Compiled by tsc --noEmit (scripts/test_web.sh): adaptive bitrate over a manifest's
// renditions, typed against abr_controller.d.mts.
import { loadM4d } from '../js/m4d.mjs';
import { AbrController, chooseRendition, type AbrSwitch, type M4dManifest } from '../js/abr_controller.mjs';

export async function playAdaptive(manifestUrl: string): Promise<AbrSwitch[]> {
  const m4d = await loadM4d();
  let frames = 0;
  const abr = new AbrController({
    manifestUrl,
    openDecoder: () => m4d.openDecoder(),
    onFrame: (frame, rendition) => { frames += frame.frameIndex >= 0 && rendition ? 1 : 0; },
    maxBufferSeconds: 4,
  });
  const manifest: M4dManifest = await abr.load();
  const first: number = chooseRendition(manifest.renditions, 0, 1e6);
  for (let gop = await abr.nextGop(); gop; gop = await abr.nextGop()) {
    if (gop.switched && gop.rendition === manifest.renditions[first].id) frames += 0;
  }
  abr.close();
  if (abr.stalls.count > frames) throw new Error(`${abr.stalls.ms} ms stalled`);
  return abr.switchLog;
}
