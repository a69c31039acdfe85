/*
 * render_frame: the smallest use of the M4D SDK's public C API. Decodes the first frame of a
 * stream, renders it headless from a camera looking at the origin, and writes a binary PPM.
 *
 *     render_frame STREAM.m4d OUT.ppm [WIDTH HEIGHT]
 *
 * C99, public headers only: m4d/m4d.h (decoding) and m4d/m4d_render.h (rendering).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "m4d/m4d.h"
#include "m4d/m4d_render.h"

/* Reads a whole file into a malloc'd buffer; NULL on failure. */
static uint8_t* read_file(const char* path, size_t* size) {
  FILE* f = fopen(path, "rb");
  if (!f) return NULL;
  uint8_t* data = NULL;
  if (fseek(f, 0, SEEK_END) == 0) {
    long n = ftell(f);
    if (n > 0 && fseek(f, 0, SEEK_SET) == 0) {
      data = malloc((size_t)n);
      if (data && fread(data, 1, (size_t)n, f) != (size_t)n) {
        free(data);
        data = NULL;
      }
      *size = (size_t)n;
    }
  }
  fclose(f);
  return data;
}

/* Sends packets until the decoder outputs a frame. 0 on success. */
static int decode_first_frame(M4dContext* ctx, const uint8_t* data, size_t size, M4dFrame* out) {
  size_t pos = 0;
  while (pos < size) {
    M4dPacketInfo info;
    if (m4d_parse_packet_header(data + pos, size - pos, &info) < 0) return -1;
    int r = m4d_send_packet(ctx, data + pos, info.packet_size);
    if (r == M4D_ERR_AGAIN) return m4d_get_frame(ctx, out);
    if (r < 0) fprintf(stderr, "packet rejected: %s\n", m4d_last_error(ctx));
    if (m4d_get_frame(ctx, out) == 0) return 0;
    pos += info.packet_size;
  }
  return -1;
}

/* A camera 4 units in front of the origin (negative z), looking at it, 60 degrees across. */
static M4dRenderCamera front_camera(uint32_t width, uint32_t height) {
  M4dRenderCamera c;
  memset(&c, 0, sizeof(c));
  c.width = width;
  c.height = height;
  c.fx = c.fy = 0.5f * (float)width / tanf(0.5f * 60.0f * 3.14159265f / 180.0f);
  c.cx = 0.5f * (float)width;
  c.cy = 0.5f * (float)height;
  c.rotation[0] = c.rotation[4] = c.rotation[8] = 1.0f; /* OpenCV axes: z forward */
  c.translation[2] = 4.0f;
  c.near_plane = 0.2f;
  return c;
}

static int write_ppm(const char* path, const uint8_t* rgb, uint32_t width, uint32_t height) {
  FILE* f = fopen(path, "wb");
  if (!f) return -1;
  fprintf(f, "P6\n%u %u\n255\n", width, height);
  size_t n = (size_t)width * height * 3;
  int ok = fwrite(rgb, 1, n, f) == n;
  return fclose(f) == 0 && ok ? 0 : -1;
}

int main(int argc, char** argv) {
  if (argc != 3 && argc != 5) {
    fprintf(stderr, "usage: %s STREAM.m4d OUT.ppm [WIDTH HEIGHT]\n", argv[0]);
    return 2;
  }
  uint32_t width = argc == 5 ? (uint32_t)strtoul(argv[3], NULL, 10) : 320;
  uint32_t height = argc == 5 ? (uint32_t)strtoul(argv[4], NULL, 10) : 240;
  size_t size = 0;
  uint8_t* data = read_file(argv[1], &size);
  if (!data) {
    fprintf(stderr, "cannot read %s\n", argv[1]);
    return 1;
  }
  M4dSettings settings;
  m4d_default_settings(&settings);
  M4dContext* ctx = NULL;
  M4dFrame frame;
  memset(&frame, 0, sizeof(frame));
  int r = m4d_open(&ctx, &settings);
  if (r == 0) r = decode_first_frame(ctx, data, size, &frame);
  free(data);
  if (r < 0) {
    fprintf(stderr, "no frame decoded from %s\n", argv[1]);
    m4d_close(&ctx);
    return 1;
  }

  M4dRendererSettings render_settings;
  m4d_renderer_default_settings(&render_settings);
  M4dRenderer* renderer = NULL;
  uint8_t* rgb = malloc((size_t)width * height * 3);
  M4dRenderCamera camera = front_camera(width, height);
  r = rgb ? m4d_renderer_open(&renderer, &render_settings) : M4D_ERR_NOMEM;
  if (r == 0) r = m4d_renderer_upload(renderer, &frame, M4D_LAYER_ALL);
  if (r == 0) r = m4d_renderer_draw(renderer, &camera);
  if (r == 0) r = m4d_renderer_read_rgb(renderer, rgb, (size_t)width * height * 3);
  if (r == 0) r = write_ppm(argv[2], rgb, width, height);
  if (r < 0) {
    fprintf(stderr, "rendering failed: %s (%s)\n", m4d_error_string(r),
            renderer ? m4d_renderer_last_error(renderer) : "no renderer");
  } else {
    M4dRenderStats stats;
    m4d_renderer_stats(renderer, &stats);
    printf("frame %u: %u splats drawn with %s into %s\n", frame.frame_index, stats.visible,
           m4d_renderer_description(renderer), argv[2]);
  }
  free(rgb);
  m4d_renderer_close(&renderer);
  m4d_frame_unref(&frame);
  m4d_close(&ctx);
  return r < 0 ? 1 : 0;
}
