#include "stream_check.h"

#include <string>

#include "common/md5.h"
#include "m4d/m4d.h"

namespace m4d {
namespace {

// Sends one packet, taking frames out when the decoder asks; appends their hashes.
int SendAndDrain(M4dContext* ctx, const uint8_t* data, size_t size,
                 std::vector<std::string>* hashes) {
  auto drain = [&]() {
    M4dFrame frame;
    while (m4d_get_frame(ctx, &frame) == M4D_OK) {
      uint8_t md5[16];
      m4d_frame_hash(&frame, md5);
      hashes->push_back(HexDigest(md5));
      m4d_frame_unref(&frame);
    }
  };
  int r = m4d_send_packet(ctx, data, size);
  if (r == M4D_ERR_AGAIN) {
    drain();
    r = m4d_send_packet(ctx, data, size);
  }
  drain();
  return r;
}

}  // namespace

Status CheckDecodedHashes(const std::vector<uint8_t>& stream, const SequenceReport& report) {
  M4dSettings settings;
  m4d_default_settings(&settings);
  M4dContext* ctx = nullptr;
  if (m4d_open(&ctx, &settings) < 0) return Status(M4D_ERR_NOMEM, "decoder check: open failed");
  std::vector<std::string> hashes;
  size_t offset = 0;
  int error = 0;
  while (offset < stream.size() && error >= 0) {
    M4dPacketInfo info;
    error = m4d_parse_packet_header(stream.data() + offset, stream.size() - offset, &info);
    if (error < 0) break;
    error = SendAndDrain(ctx, stream.data() + offset, info.packet_size, &hashes);
    offset += info.packet_size;
  }
  m4d_close(&ctx);
  if (error < 0) {
    return Status(M4D_ERR_BITSTREAM, std::string("decoder check: ") + m4d_error_string(error));
  }
  if (hashes.size() != report.frames.size()) {
    return Status(M4D_ERR_BITSTREAM, "decoder check: " + std::to_string(hashes.size()) +
                                         " frames decoded, " +
                                         std::to_string(report.frames.size()) + " encoded");
  }
  for (size_t f = 0; f < hashes.size(); ++f) {
    if (hashes[f] != report.frames[f].hash) {
      return Status(M4D_ERR_BITSTREAM,
                    "decoder check: frame " + std::to_string(f) + " differs from the encoder's");
    }
  }
  return Status::Ok();
}

}  // namespace m4d
