/*
 * m4d_render.h - OpenGL ES renderer of decoded M4D frames.
 *
 * Draws the Gaussians of a frame (m4d.h) with OpenGL ES 3.0, with the splat model of the
 * SDK's CPU reference rasterizer: the same projection, opacity and SH colour per view, splats
 * blended front to back in depth order (premultiplied colour), the background composited
 * last. Projection, SH evaluation and the depth sort run on the CPU (threads); the GPU (or
 * Mesa's llvmpipe) rasterizes one quad per visible splat.
 *
 * Two ways to use it:
 *  - headless (default): the renderer makes its own context (EGL's surfaceless platform,
 *    else EGL's default display, else OSMesa when libOSMesa is installed) and renders into
 *    its own framebuffer; read the image back with m4d_renderer_read_rgb.
 *  - in the caller's context: the caller's OpenGL ES 3.0 context is current on the calling
 *    thread for every call (open included); m4d_renderer_draw draws into the framebuffer
 *    bound for drawing, over the whole viewport the caller set, and changes only the GL state
 *    it documents.
 *
 * Typical use:
 *
 *     M4dRendererSettings s;
 *     m4d_renderer_default_settings(&s);
 *     M4dRenderer *r;
 *     if (m4d_renderer_open(&r, &s) < 0) ...
 *     for each decoded frame f:
 *         m4d_renderer_upload(r, &f, M4D_LAYER_ALL);
 *         m4d_renderer_draw(r, &camera);
 *         m4d_renderer_read_rgb(r, rgb, camera.width * camera.height * 3);
 *     m4d_renderer_close(&r);
 *
 * Every function returns 0 or a negative M4D_ERR_* code of m4d.h. A renderer is used by one
 * thread at a time.
 */
#ifndef M4D_M4D_RENDER_H_
#define M4D_M4D_RENDER_H_

#include <stddef.h>
#include <stdint.h>

#include "m4d/m4d.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Where the renderer draws (M4dRendererSettings.context). */
typedef enum M4dRenderContext {
  M4D_RENDER_HEADLESS = 0,       /* its own context and framebuffer */
  M4D_RENDER_CURRENT_CONTEXT = 1 /* the caller's current context and draw framebuffer */
} M4dRenderContext;

/* A pinhole camera with OpenCV axes (x right, y down, z forward) and COLMAP's pixel grid:
 * a camera-space point (X, Y, Z) lands at u = fx X / Z + cx, v = fy Y / Z + cy, pixel (i, j)
 * (row 0 at the top) has its centre at (i + 0.5, j + 0.5). */
typedef struct M4dRenderCamera {
  uint32_t width, height; /* image size in pixels, 1..16384 each */
  float fx, fy;           /* focal lengths in pixels */
  float cx, cy;           /* principal point in pixels */
  float rotation[9];      /* world-to-camera rotation, row-major (orthonormal) */
  float translation[3];   /* x_cam = rotation * x_world + translation */
  float near_plane;       /* Gaussians at depth <= near_plane are culled; e.g. 0.2 */
  uint8_t reserved[16];   /* zero (memset the struct); room for later fields */
} M4dRenderCamera;

/* Renderer settings. Always initialise with m4d_renderer_default_settings(). */
typedef struct M4dRendererSettings {
  /* M4D_RENDER_HEADLESS or M4D_RENDER_CURRENT_CONTEXT. Default: M4D_RENDER_HEADLESS. */
  int context;
  /* Entry point loader of the caller's context (M4D_RENDER_CURRENT_CONTEXT only), e.g.
   * eglGetProcAddress; NULL: eglGetProcAddress. Default: NULL. */
  void (*(*get_proc_address)(const char* name))(void);
  /* CPU threads for projection and sorting; 0: all cores. Default: 0. */
  int threads;
  /* Largest SH degree evaluated (0..3); lower is faster. Default: 3. */
  int sh_degree;
  /* Largest Gaussian count accepted by m4d_renderer_upload (both layers together); 0 means
   * 2^23. Default: 0. */
  uint32_t max_gaussians;
  /* Colour behind the splats, linear RGB in [0, 1]. Default: black. */
  float background[3];
  M4dLogger logger;     /* default: no logging */
  uint8_t reserved[32]; /* for future settings; must stay zero */
} M4dRendererSettings;

/* Time spent in the last m4d_renderer_draw, by stage, in milliseconds of wall time. */
typedef struct M4dRenderStats {
  uint32_t visible;  /* splats drawn after culling */
  double project_ms; /* projection, opacity and SH colour per Gaussian (CPU) */
  double sort_ms;    /* depth sort of the visible splats (CPU) */
  double upload_ms;  /* instance data to the GL buffer */
  double draw_ms;    /* GL draw calls until finished (glFinish) */
  uint8_t reserved[32];
} M4dRenderStats;

/* Opaque renderer. */
typedef struct M4dRenderer M4dRenderer;

/* Fills *s with the defaults documented in M4dRendererSettings. */
M4D_API void m4d_renderer_default_settings(M4dRendererSettings* s);

/* Creates a renderer: its context (headless) or its GL objects in the caller's current
 * context. On failure *r_out is NULL. M4D_ERR_INVALID_ARG for NULL arguments, a bad setting
 * or non-zero reserved bytes; M4D_ERR_UNSUPPORTED when no OpenGL ES 3.0 context can be made
 * or used (the reason goes to the logger). */
M4D_API int m4d_renderer_open(M4dRenderer** r_out, const M4dRendererSettings* s);

/* Copies the Gaussians of frame's layers selected by `layers` (M4D_LAYER_* bits; layers the
 * frame does not carry are skipped) for the next draws; the frame may be released after the
 * call. M4D_ERR_INVALID_ARG for NULL arguments or inconsistent layer arrays, M4D_ERR_LIMIT
 * above max_gaussians, M4D_ERR_NOMEM. */
M4D_API int m4d_renderer_upload(M4dRenderer* r, const M4dFrame* frame, uint32_t layers);

/* Renders the uploaded Gaussians from *camera. Headless: into the renderer's framebuffer of
 * the camera's size. In the caller's context: into the bound draw framebuffer's viewport,
 * which should have the camera's size; blending, depth and stencil tests, face culling, the
 * program, vertex array and array buffer bindings are changed and not restored.
 * M4D_ERR_INVALID_ARG for NULL arguments or a bad camera (non-zero reserved bytes included). */
M4D_API int m4d_renderer_draw(M4dRenderer* r, const M4dRenderCamera* camera);

/* Headless only: reads the last draw as width * height RGB bytes, row 0 at the top, into
 * rgb (size bytes available). M4D_ERR_INVALID_ARG without a headless draw or when size is
 * too small. */
M4D_API int m4d_renderer_read_rgb(M4dRenderer* r, uint8_t* rgb, size_t size);

/* Fills *stats with the timings of the last m4d_renderer_draw. */
M4D_API int m4d_renderer_stats(const M4dRenderer* r, M4dRenderStats* stats);

/* Returns the last error message of the renderer (empty when none). Valid until the next
 * call on the renderer. */
M4D_API const char* m4d_renderer_last_error(const M4dRenderer* r);

/* Returns which context the renderer draws with, e.g. "surfaceless, llvmpipe (LLVM 15.0.6,
 * 256 bits)". Never NULL; valid while the renderer is open. */
M4D_API const char* m4d_renderer_description(const M4dRenderer* r);

/* Releases the renderer (in the caller's context: that context must be current) and sets
 * *r to NULL. Safe on NULL and on *r == NULL. */
M4D_API void m4d_renderer_close(M4dRenderer** r);

#ifdef __cplusplus
}
#endif

#endif /* M4D_M4D_RENDER_H_ */
