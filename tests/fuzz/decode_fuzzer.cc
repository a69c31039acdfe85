// libFuzzer target for the whole decode path: the input is a stream; the first byte picks
// the output layers, the checksum mode and a decoder Gaussian limit. Packets are split with
// the public header parser (resynchronising on the sync word after damage) and fed through
// the public API, frames are hashed (reading every output array).
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "m4d/m4d.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const uint8_t mode = data[0];
  ++data;
  --size;
  M4dSettings s;
  m4d_default_settings(&s);
  const uint32_t layer_choice[4] = {M4D_LAYER_ALL, M4D_LAYER_STATIC, M4D_LAYER_DYNAMIC,
                                    M4D_LAYER_ALL};
  s.layers = layer_choice[mode & 3];
  // Most inputs come from mutated seeds whose CRCs no longer match: let many of them through
  // to the payload parsers by skipping the payload check.
  s.verify_checksums = (mode & 4) ? 1 : 0;
  s.max_gaussians = (mode & 8) ? 1000 : 0;
  M4dContext* ctx = nullptr;
  if (m4d_open(&ctx, &s) != M4D_OK) return 0;
  size_t pos = 0;
  while (pos + 24 <= size) {
    M4dPacketInfo info;
    const int r = m4d_parse_packet_header(data + pos, size - pos, &info);
    if (r != M4D_OK) {
      ++pos;  // resynchronise
      continue;
    }
    if (m4d_send_packet(ctx, data + pos, info.packet_size) == M4D_ERR_AGAIN) {
      M4dFrame frame;
      while (m4d_get_frame(ctx, &frame) == M4D_OK) m4d_frame_unref(&frame);
      m4d_send_packet(ctx, data + pos, info.packet_size);
    }
    M4dFrame frame;
    while (m4d_get_frame(ctx, &frame) == M4D_OK) {
      uint8_t md5[16];
      m4d_frame_hash(&frame, md5);
      m4d_frame_unref(&frame);
    }
    if (mode & 16 && pos == 0) m4d_flush(ctx);
    pos += info.packet_size;
  }
  m4d_close(&ctx);
  return 0;
}
