// Type declarations of m4d.mjs (TypeScript finds them beside it), the M4D decoder for JavaScript (see its comments).

/** Which layers a decoder outputs or a renderer draws. */
export type M4dLayers = 'all' | 'static' | 'dynamic';

/** One layer's Gaussians, values as coded; views of the module's memory. */
export interface M4dLayerView {
  count: number;
  shDegree: number;
  /** (shDegree + 1)^2 per colour channel. */
  shCoefficients: number;
  /** 3 per Gaussian. */
  positions: Float32Array;
  /** 3 per Gaussian (natural log). */
  logScales: Float32Array;
  /** 4 per Gaussian: w, x, y, z (not normalised). */
  rotations: Float32Array;
  /** 1 per Gaussian. */
  opacityLogits: Float32Array;
  /** 3 * shCoefficients per Gaussian: [k][r, g, b]. */
  sh: Float32Array;
}

/** A decoded frame, valid until the decoder's next call. */
export interface M4dFrame {
  frameIndex: number;
  isKeyframe: boolean;
  /** Bits: 1 static, 2 dynamic. */
  layers: number;
  /** Bits of the layers lost to damage and concealed (bitstream-spec 6.8); 0 when intact. */
  concealedLayers: number;
  static: M4dLayerView;
  dynamic: M4dLayerView;
  /** The normative frame hash (bitstream-spec 7), 32 hex digits. */
  hash(): string;
}

export interface M4dStreamInfo {
  bitstreamVersion: string;
  profile: number;
  shDegree: number;
  fps: number;
  fpsNum: number;
  fpsDen: number;
  numFrames: number;
  staticLayerCoded: boolean;
  framesDecoded: number;
  gops: number;
  randomAccessGops: number;
  lastKeyframeIndex: number;
  lastRandomAccessIndex: number;
  /** The world's up as a unit axis vector, or null when the stream does not state it. */
  upAxis: [number, number, number] | null;
}

/** Damage met so far. Codes are M4D_ERR_* values, or -100 ('TRUNCATED'). */
export interface M4dErrors {
  count: number;
  firstCode: number;
  firstCodeName: string;
  lastOffset: number;
  lastCode: number;
  lastCodeName: string;
  lastMessage: string;
}

export interface M4dDecoderOptions {
  layers?: M4dLayers;
  /** Largest Gaussian count accepted in a layer; 0 (default): the spec's limit. */
  maxGaussians?: number;
}

export declare class M4dDecoder {
  push(bytes: Uint8Array | ArrayBuffer): void;
  end(): void;
  nextFrame(): M4dFrame | null;
  seek(frameIndex: number): boolean;
  streamInfo(): M4dStreamInfo | null;
  setBackground(source: M4dDecoder | null): void;
  readonly errors: M4dErrors;
  readonly skippedBytes: number;
  readonly bufferedBytes: number;
  close(): void;
}

/** World to camera, OpenCV axes, in pixels of the canvas's drawing buffer. */
export interface M4dCamera {
  fx: number;
  fy: number;
  cx: number;
  cy: number;
  /** 9 values, row-major. */
  rotation: ArrayLike<number>;
  translation: ArrayLike<number>;
  /** Default 0.2. */
  near?: number;
}

export interface M4dRenderStats {
  visible: number;
  projectMs: number;
  sortMs: number;
  uploadMs: number;
  drawMs: number;
}

export declare class M4dRenderer {
  upload(decoder: M4dDecoder, layers?: M4dLayers): void;
  draw(camera: M4dCamera): void;
  stats(): M4dRenderStats;
  lastError(): string;
  close(): void;
}

export interface M4dRendererOptions {
  /** Linear RGB behind the splats; default black. */
  background?: [number, number, number];
  /** Largest SH degree evaluated, 0..3; default 3. */
  shDegree?: number;
}

export declare class M4d {
  version(): string;
  errorString(code: number): string;
  openDecoder(options?: M4dDecoderOptions): M4dDecoder;
  /** The canvas needs an id. */
  openRenderer(canvas: HTMLCanvasElement, options?: M4dRendererOptions): M4dRenderer;
}

export declare function loadM4d(options?: { wasmBinary?: ArrayBuffer | Uint8Array }): Promise<M4d>;
export declare function errorCodeName(code: number): string;
