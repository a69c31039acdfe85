// Type declarations of worker_decoder.mjs: the M4D decoder in a Web Worker.
import type { M4dErrors, M4dLayers, M4dStreamInfo } from './m4d.mjs';
import type { SplatFrame } from './splat_frame.mjs';

export interface M4dWorkerDecoderOptions {
  /** The worker script; default m4d_worker.mjs beside worker_decoder.mjs. */
  workerUrl?: string | URL;
  /** m4d.mjs as the worker imports it; default beside the worker script. */
  moduleUrl?: string | URL;
  /** m4d_wasm.wasm; default beside m4d_wasm.mjs. */
  wasmUrl?: string | URL;
  wasmBinary?: ArrayBuffer | Uint8Array;
  layers?: M4dLayers;
  maxGaussians?: number;
}

export declare class M4dWorkerDecoder {
  constructor(options?: M4dWorkerDecoderOptions);
  readonly info: M4dStreamInfo | null;
  readonly errors: M4dErrors | null;
  readonly ended: boolean;
  readonly lastDecodeMs: number;
  open(): Promise<{ version: string }>;
  push(bytes: Uint8Array | ArrayBuffer, options?: { transfer?: boolean }): Promise<{ bufferedBytes: number }>;
  end(): Promise<void>;
  seek(frame: number): Promise<boolean>;
  nextFrame(): Promise<SplatFrame | null>;
  streamInfo(): M4dStreamInfo | null;
  close(): void;
}
