// Type declarations of abr_controller.mjs (adaptive bitrate over m4d renditions; see its comments).
import type { M4dDecoder, M4dFrame } from './m4d.mjs';

/** A GOP of a stream, as in the GOP index and the manifest. */
export interface M4dGopEntry {
  frame: number;
  frames: number;
  offset: number;
  bytes: number;
  random_access: boolean;
}

export interface M4dRendition {
  id: string;
  /** Relative to the manifest. */
  url: string;
  rate_point: string;
  /** Bits per second over the whole stream. */
  bandwidth: number;
  bytes: number;
  gops: M4dGopEntry[];
}

/** OUT.manifest.json of `m4d encode --renditions`; renditions sorted by bandwidth, ascending. */
export interface M4dManifest {
  format: 'm4d-manifest';
  version: 1;
  frames: number;
  fps: number;
  renditions: M4dRendition[];
}

export interface AbrOptions {
  manifestUrl: string;
  openDecoder: () => M4dDecoder;
  onFrame?: (frame: M4dFrame, renditionId: string) => void;
  fetch?: (url: string, init?: { headers?: Record<string, string> }) => Promise<Response>;
  /** Step down when bandwidth > safety * throughput; default 0.75. */
  safety?: number;
  /** Step up when bandwidth * upMargin <= smoothed throughput; default 1.5. */
  upMargin?: number;
  /** Weight of a new measure in the smoothed throughput; default 0.5. */
  smoothing?: number;
  /** Content fetched ahead of the playhead; default 2. */
  maxBufferSeconds?: number;
  /** The first rendition's id; default the lowest. */
  start?: string;
}

export interface AbrSwitch {
  frame: number;
  from: string;
  to: string;
  /** Bits per second. */
  throughput: number;
  /** Milliseconds since the first fetch. */
  time: number;
}

export interface AbrStalls {
  count: number;
  ms: number;
  list: { frame: number; ms: number }[];
}

export interface AbrGopResult {
  gop: number;
  frame: number;
  frames: number;
  rendition: string;
  bytes: number;
  seconds: number;
  /** This fetch's, bits per second. */
  throughput: number;
  stallMs: number;
  switched: boolean;
  decodedFrames: number;
}

export declare function validateManifest(manifest: unknown): M4dManifest;
export declare function chooseRendition(
  renditions: { bandwidth: number }[], current: number, estimate: number,
  options?: { safety?: number; upMargin?: number }): number;

export declare class AbrController {
  constructor(options: AbrOptions);
  load(): Promise<M4dManifest>;
  readonly manifest: M4dManifest | null;
  readonly rendition: string;
  readonly throughput: number;
  readonly switchLog: AbrSwitch[];
  readonly stalls: AbrStalls;
  readonly done: boolean;
  nextGop(): Promise<AbrGopResult | null>;
  run(): Promise<AbrSwitch[]>;
  fetchRange(url: string, offset: number, length: number): Promise<Uint8Array>;
  /** The throughput estimate decisions use, bits per second. */
  decisionEstimate(): number;
  /** Restarts at the random-access GOP at or before `frame`; returns its first frame. */
  seek(frame: number): number;
  /** The decoder of the current rendition, or null. */
  readonly decoder: M4dDecoder | null;
  readonly options: AbrOptions & { maxBufferSeconds: number };
  close(): void;
}
