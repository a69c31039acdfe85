// Type declarations of playcanvas_adapter.mjs, the PlayCanvas engine adapter (see its comments).
// PlayCanvas's objects are typed structurally (the few members the adapter uses): the
// playcanvas package's declarations need a newer TypeScript than the project's.

/** A pc.Entity. */
export interface PlayCanvasEntity {
  addChild(child: PlayCanvasEntity): void;
  getGuid(): string;
  destroy(): void;
  [member: string]: unknown;
}

/** A pc.AppBase. */
export interface PlayCanvasApp {
  graphicsDevice: object;
  root: PlayCanvasEntity;
}

/** The playcanvas module (import * as pc from 'playcanvas'). */
export interface PlayCanvasModule {
  GSplatData: new (...args: any[]) => object;
  GSplatResource: new (...args: any[]) => object;
  Entity: new (name?: string) => PlayCanvasEntity;
  Mat4: new () => object;
  Quat: new () => object;
  [member: string]: unknown;
}

import type { M4dCamera } from '../js/m4d.mjs';
import type { SplatFrame } from '../js/splat_frame.mjs';
export type { SplatFrame, SplatLayer } from '../js/splat_frame.mjs';

/** What update() did so far. */
export interface M4dPlayCanvasStats {
  frames: number;
  staticBuilds: number;
  dynamicBuilds: number;
  dynamicInPlace: number;
  lastUpdateMs: number;
}

export interface M4dPlayCanvasOptions {
  /** The entity the layers' entities go under; default app.root. */
  parent?: PlayCanvasEntity;
  /** Largest SH degree drawn, 0..3; default 3. */
  shDegree?: number;
}

export declare class M4dPlayCanvasAdapter {
  constructor(app: PlayCanvasApp, pc: PlayCanvasModule, options?: M4dPlayCanvasOptions);
  readonly stats: M4dPlayCanvasStats;
  readonly entities: { static: PlayCanvasEntity | null; dynamic: PlayCanvasEntity | null };
  /** Returns the milliseconds the CPU side took. */
  update(frame: SplatFrame): number;
  destroy(): void;
}

/** A capture camera: world to camera, OpenCV axes, in pixels of a width x height image. */
export interface M4dCaptureCamera extends M4dCamera {
  /** Default 1000. */
  far?: number;
}

export declare function setCaptureCamera(pc: PlayCanvasModule, cameraEntity: PlayCanvasEntity, camera: M4dCaptureCamera,
  width?: number, height?: number): void;
