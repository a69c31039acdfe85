/*
 * frame_hashes: decodes a whole stream with the M4D SDK's public C API and prints one line per
 * decoded frame, "<frame index> <MD5 of the frame (bitstream-spec 7)>", the format of the
 * conformance suite's .md5 files. Damaged packets are reported on stderr and decoding goes on
 * at the next GOP; the exit status is 1 if any packet was rejected.
 *
 *     frame_hashes STREAM.m4d
 *
 * C99, m4d/m4d.h only: it is also what the out-of-tree consumers (examples/consumers) build
 * against an installed SDK.
 */
#include <stdio.h>
#include <stdlib.h>

#include "m4d/m4d.h"

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

/* Prints and releases every frame the decoder has ready. */
static void drain(M4dContext* ctx) {
  M4dFrame frame;
  while (m4d_get_frame(ctx, &frame) == M4D_OK) {
    uint8_t md5[16];
    if (m4d_frame_hash(&frame, md5) == M4D_OK) {
      printf("%u ", frame.frame_index);
      for (int i = 0; i < 16; ++i) printf("%02x", md5[i]);
      printf("\n");
    }
    m4d_frame_unref(&frame);
  }
}

int main(int argc, char** argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: frame_hashes STREAM.m4d   (SDK %s)\n", m4d_version());
    return 2;
  }
  size_t size = 0;
  uint8_t* data = read_file(argv[1], &size);
  if (!data) {
    fprintf(stderr, "cannot read %s\n", argv[1]);
    return 2;
  }
  M4dSettings settings;
  m4d_default_settings(&settings);
  M4dContext* ctx = NULL;
  int rejected = 0;
  if (m4d_open(&ctx, &settings) != M4D_OK) {
    free(data);
    return 2;
  }
  size_t pos = 0;
  while (pos < size) {
    size_t offset = 0;
    M4dPacketInfo info;
    if (m4d_find_packet(data + pos, size - pos, &offset, &info) != M4D_OK) break;
    if (offset > 0) {
      /* Skipped bytes may have held a packet: start again at the next GOP (m4d.h). */
      fprintf(stderr, "%zu bytes skipped at byte %zu\n", offset, pos);
      m4d_flush(ctx);
      rejected = 1;
    }
    pos += offset;
    int r;
    while ((r = m4d_send_packet(ctx, data + pos, info.packet_size)) == M4D_ERR_AGAIN) drain(ctx);
    if (r < 0) {
      fprintf(stderr, "packet at byte %zu rejected: %s\n", pos, m4d_last_error(ctx));
      rejected = 1;
    }
    drain(ctx);
    pos += info.packet_size;
  }
  drain(ctx);
  m4d_close(&ctx);
  free(data);
  return rejected;
}
