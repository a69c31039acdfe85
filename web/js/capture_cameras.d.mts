// Type declarations of capture_cameras.mjs.

/** A capture camera of a transforms.json: OpenCV axes, pixels of a width x height image; world to camera. */
export interface TransformsCamera {
  name: string;
  width: number;
  height: number;
  fx: number;
  fy: number;
  cx: number;
  cy: number;
  /** 9 values, row-major. */
  rotation: number[];
  translation: number[];
}

/** One camera per distinct camera of a transforms.json's frames; a TypeError without a frames array. */
export declare function camerasOfTransforms(json: unknown): TransformsCamera[];
