// Type declarations of splat_frame.mjs: owned SplatLayer/SplatFrame copies and conversions.
import type { M4dFrame, M4dLayerView, M4dStreamInfo } from './m4d.mjs';

/** One layer's Gaussians as coded (the fields of M4dLayerView), each array owning its buffer. */
export interface SplatLayer extends M4dLayerView {}

/** A decoded frame handed between threads and to the viewer adapters. */
export interface SplatFrame {
  frameIndex: number;
  isKeyframe: boolean;
  /** Bits: 1 static, 2 dynamic. */
  layers: number;
  /** Bits of the layers concealed after damage; 0 when intact. */
  concealedLayers: number;
  /** True when `static` differs from the previous frame delivered (first frame, keyframe, seek). */
  staticChanged: boolean;
  /** Null when staticChanged is false: the previous static layer still holds. */
  static: SplatLayer | null;
  dynamic: SplatLayer;
}

export declare const SH_C0: number;
export declare function copySplatLayer(layerView: M4dLayerView | SplatLayer): SplatLayer;
export declare function splatFrameFromDecoder(frame: M4dFrame, options?: { staticChanged?: boolean }): SplatFrame;
/** SplatFrames from a main-thread decoder's frames, with staticChanged set from the layers. */
export declare class SplatFrameMaker {
  constructor();
  /** The static layer last sent (an owned copy), or null. */
  readonly lastStatic: SplatLayer | null;
  /** The next frame carries its static layer (call after a seek). */
  reset(): void;
  make(frame: M4dFrame): SplatFrame;
}
/** A PlayerCore frame source over a main-thread M4dDecoder or a GopStreamer. */
export declare class DecoderFrameSource {
  constructor(producer: { nextFrame(): M4dFrame | null | Promise<M4dFrame | null>; seek(frame: number): boolean | void });
  readonly ended: boolean;
  readonly lastDecodeMs: number;
  nextFrame(): Promise<SplatFrame | null>;
  seek(frame: number): Promise<boolean>;
  streamInfo(): M4dStreamInfo | null;
}
export declare function transferablesOf(splatFrame: SplatFrame): ArrayBuffer[];
export declare function layersEqual(a: M4dLayerView | SplatLayer | null, b: M4dLayerView | SplatLayer | null): boolean;
export declare function linearScales(layer: M4dLayerView | SplatLayer, out?: Float32Array): Float32Array;
export declare function opacities(layer: M4dLayerView | SplatLayer, out?: Float32Array): Float32Array;
export declare function normalisedRotationsXyzw(layer: M4dLayerView | SplatLayer, out?: Float32Array): Float32Array;
export declare function rgbFromShDc(layer: M4dLayerView | SplatLayer, out?: Float32Array): Float32Array;
