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

// The controller as a PlayerCore frame source (abr_frame_source.d.mts).
import { AbrFrameSource } from '../js/abr_frame_source.mjs';
import { PlayerCore } from '../js/player_core.mjs';

export async function playerOverManifest(manifestUrl: string): Promise<string | null> {
  const m4d = await loadM4d();
  const source = await AbrFrameSource.open(new AbrController({ manifestUrl, openDecoder: () => m4d.openDecoder() }));
  const core = new PlayerCore(source);
  core.play();
  const frame = await source.nextFrame();
  const switches: AbrSwitch[] = source.switchLog;
  await source.seek(switches.length ? switches[0].frame : 0);
  await source.close();
  return frame && frame.staticChanged ? frame.rendition : source.rendition;
}
