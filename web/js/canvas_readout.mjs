// Reads back what a WebGL context drew, as the tests compare it with the native renderer's PNGs.

/**
 * The pixels of the framebuffer bound to gl (width x height from its bottom-left corner) as
 * RGB bytes, top row first: WebGL's rows come bottom first and with alpha.
 */
export function readRgb(gl, width, height) {
  const rgba = new Uint8Array(4 * width * height);
  gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, rgba);
  const rgb = new Uint8Array(3 * width * height);
  for (let y = 0; y < height; ++y) {
    for (let x = 0; x < width; ++x) {
      const from = 4 * ((height - 1 - y) * width + x), to = 3 * (y * width + x);
      rgb[to] = rgba[from]; rgb[to + 1] = rgba[from + 1]; rgb[to + 2] = rgba[from + 2];
    }
  }
  return rgb;
}
