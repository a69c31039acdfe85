// Type declarations of gop_streamer.mjs: an M4D stream played over HTTP by GOP with range
// requests, from its GOP index (see the module's comments).
import type { M4d, M4dDecoder, M4dFrame, M4dLayers } from './m4d.mjs';

/** One GOP of the index (m4d_probe --gop-index). */
export interface GopEntry {
  /** frame_index of its keyframe. */
  frame: number;
  frames: number;
  /** Byte offset of its first packet. */
  offset: number;
  bytes: number;
  /** Its keyframe starts with a SEQUENCE_HEADER: decoding can start there. */
  random_access: boolean;
}

/** The GOP index sidecar, STREAM.m4d.gops.json. */
export interface GopIndex {
  format: 'm4d-gop-index';
  version: 1;
  stream_bytes: number;
  frames: number;
  fps: number;
  gops: GopEntry[];
}

export declare const GOP_INDEX_FORMAT: 'm4d-gop-index';
export declare const GOP_INDEX_VERSION: 1;

/** HTTP failure, a server without range requests, an index that does not match the stream. */
export declare class GopStreamError extends Error {}

/** Checks a parsed index; returns it or throws GopStreamError. */
export declare function checkGopIndex(index: unknown, where?: string): GopIndex;

export interface GopStreamerOptions {
  /** The loaded module (loadM4d). */
  m4d: M4d;
  url: string;
  /** Default: url + '.gops.json'. */
  indexUrl?: string;
  layers?: M4dLayers;
  /** GOPs past the one playing requested ahead; default 1. */
  readAhead?: number;
  fetch?: typeof fetch;
}

export interface GopRequest {
  gop: number;
  /** Inclusive byte range. */
  start: number;
  end: number;
}

export declare class GopStreamer {
  static open(options: GopStreamerOptions): Promise<GopStreamer>;
  readonly index: GopIndex;
  readonly frames: number;
  readonly fps: number;
  /** The decoder frames come from; replaced at each seek. */
  readonly decoder: M4dDecoder;
  /** Body bytes received over every request, the index included. */
  readonly bytesFetched: number;
  readonly requests: GopRequest[];
  gopOf(frame: number, from?: number): number;
  randomAccessGopOf(frame: number): number;
  /** The next frame (valid until the next call), or null at the end. */
  nextFrame(): Promise<M4dFrame | null>;
  seek(frame: number): void;
  close(): void;
}
