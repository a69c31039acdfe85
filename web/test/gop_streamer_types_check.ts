// Compiled by tsc --noEmit (scripts/test_web.sh): a page playing a stream by GOP over HTTP,
// typed against gop_streamer.d.mts.
import { loadM4d } from '../js/m4d.mjs';
import { GopStreamError, GopStreamer, type GopEntry } from '../js/gop_streamer.mjs';

export async function playFrom(url: string, frame: number): Promise<string[]> {
  const m4d = await loadM4d();
  const streamer = await GopStreamer.open({ m4d, url, readAhead: 1 });
  const start: GopEntry = streamer.index.gops[streamer.randomAccessGopOf(frame)];
  streamer.seek(frame);
  const hashes: string[] = [];
  try {
    for (let f; (f = await streamer.nextFrame()); ) hashes.push(`${f.frameIndex} ${f.hash()}`);
  } catch (error) {
    if (error instanceof GopStreamError) return [error.message, String(start.offset)];
    throw error;
  } finally {
    streamer.close();
  }
  return hashes;
}
