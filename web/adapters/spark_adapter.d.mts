// Type declarations of spark_adapter.mjs, the M4D adapter for three.js with Spark. THREE and
// Spark are passed in as modules; their types are left open here (no dependency on them).

import type { M4dCamera } from '../js/m4d.mjs';
import type { SplatFrame, SplatLayer } from '../js/splat_frame.mjs';
export type { SplatFrame, SplatLayer } from '../js/splat_frame.mjs';
export { camerasOfTransforms } from '../js/capture_cameras.mjs';

/** A capture camera: OpenCV axes, pixels; world to camera. */
export interface CaptureCamera extends M4dCamera {
  far?: number;
  width?: number;
  height?: number;
  name?: string;
}

export interface M4dSparkAdapterOptions {
  /** The `three` module. */
  THREE: any;
  /** The `@sparkjsdev/spark` module. */
  spark: any;
  /** A THREE.Scene or Object3D. */
  parent: any;
  /** Largest SH degree given to Spark, 0..3 (default 3). */
  maxSh?: number;
  /** The stream's up axis, turned to three.js's +y (default: the capture's world as is). */
  upAxis?: [number, number, number];
}

export interface M4dSparkAdapterStats {
  staticUploads: number;
  dynamicUploads: number;
  staticReallocations: number;
  dynamicReallocations: number;
  staticCount: number;
  dynamicCount: number;
}

export declare class M4dSparkAdapter {
  constructor(options: M4dSparkAdapterOptions);
  /** THREE.Group holding both layers. */
  readonly root: any;
  readonly frame: { frameIndex: number; isKeyframe: boolean } | null;
  readonly lastUpdateMs: number;
  readonly stats: M4dSparkAdapterStats;
  /** The two SplatMeshes. */
  readonly meshes: { static: any; dynamic: any };
  setUpAxis(up: ArrayLike<number>): void;
  update(frame: SplatFrame): { staticUploaded: boolean; dynamicReallocated: boolean; ms: number };
  applyCaptureCamera(camera: any, capture: CaptureCamera, width: number, height: number): void;
  dispose(): void;
}

export declare function checkLayer(layer: SplatLayer, name?: string): void;
export declare function m4dSparkRendererOptions(): {
  preBlurAmount: number; blurAmount: number; sortRadial: boolean; minAlpha: number; maxStdDev: number; enableLod: boolean;
};
export declare function applyCaptureCamera(THREE: any, camera: any, capture: CaptureCamera, width: number, height: number, worldMatrix?: any): void;
export declare function fitCaptureCamera<T extends CaptureCamera & { width: number; height: number }>(camera: T, width: number, height: number): T;
