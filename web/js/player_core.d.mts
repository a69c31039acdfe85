// Type declarations of player_core.mjs: the clock and frame pacing of a player.
import type { SplatFrame } from './splat_frame.mjs';

/** Anything that hands out frames in order: M4dWorkerDecoder, a GOP streamer, a test double. */
export interface FrameSource<F extends { frameIndex: number } = SplatFrame> {
  nextFrame(): Promise<F | null>;
  seek(frame: number): Promise<boolean>;
  streamInfo?(): { fps: number } | null;
  /** True once no more frames will come. */
  readonly ended?: boolean;
}

export interface PlayerCoreOptions {
  /** Overrides the stream's frame rate. */
  fps?: number;
  /** Frames decoded ahead; default 3. */
  maxQueue?: number;
  /** The lag after which the clock is moved back to the frame shown; default 1000. */
  maxLagMs?: number;
}

export interface PlayerCoreStats {
  shown: number;
  dropped: number;
  stalls: number;
  resyncs: number;
}

export declare class PlayerCore<F extends { frameIndex: number } = SplatFrame> {
  constructor(source: FrameSource<F>, options?: PlayerCoreOptions);
  readonly playing: boolean;
  readonly current: F | null;
  readonly error: Error | null;
  readonly stats: PlayerCoreStats;
  readonly fps: number;
  readonly ended: boolean;
  play(): void;
  pause(): void;
  /** Paused: the next tick shows the next frame. */
  step(): void;
  seek(frame: number): Promise<boolean>;
  tick(nowMs: number): F | null;
}
