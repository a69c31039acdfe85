// Type declarations of canvas_readout.mjs.

/** The framebuffer bound to gl, width x height from its bottom-left corner, as RGB bytes, top row first. */
export declare function readRgb(gl: WebGLRenderingContext | WebGL2RenderingContext, width: number, height: number): Uint8Array;
