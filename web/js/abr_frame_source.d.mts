// Type declarations of abr_frame_source.mjs (AbrController as a PlayerCore frame source).
import type { AbrController, AbrStalls, AbrSwitch } from './abr_controller.mjs';
import type { M4dStreamInfo } from './m4d.mjs';
import type { SplatFrame } from './splat_frame.mjs';

/** A SplatFrame with the rendition it was decoded from. */
export type AbrSplatFrame = SplatFrame & { rendition: string };

export declare class AbrFrameSource {
  constructor(controller: AbrController, options?: { maxFrames?: number });
  /** Loads the manifest (unless loaded) and starts fetching. */
  static open(controller: AbrController, options?: { maxFrames?: number }): Promise<AbrFrameSource>;
  readonly controller: AbrController;
  readonly ended: boolean;
  readonly lastDecodeMs: number;
  readonly shownRendition: string | null;
  readonly error: Error | null;
  readonly maxFrames: number;
  readonly rendition: string;
  readonly switchLog: AbrSwitch[];
  readonly stalls: AbrStalls;
  start(): void;
  nextFrame(): Promise<AbrSplatFrame | null>;
  seek(frame: number): Promise<boolean>;
  streamInfo(): M4dStreamInfo | { fps: number } | null;
  close(): Promise<void>;
}
