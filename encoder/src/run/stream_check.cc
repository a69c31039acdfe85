#include "encoder/src/run/stream_check.h"

#include <chrono>
#include <string>

#include "m4d/m4d.h"
#include "sdk/src/common/md5.h"

namespace m4d {
namespace {

using Clock = std::chrono::steady_clock;

// Sends one packet, taking frames out when the decoder asks. Time spent decoding accrues in
// *pending until a frame comes out, which then gets it.
int SendAndDrain(M4dContext* ctx, const uint8_t* data, size_t size, double* pending,
                 DecodedStream* out) {
  Clock::time_point start = Clock::now();
  auto drain = [&]() {
    M4dFrame frame;
    while (m4d_get_frame(ctx, &frame) == M4D_OK) {
      const Clock::time_point now = Clock::now();
      *pending += std::chrono::duration<double>(now - start).count();
      out->seconds.push_back(*pending);
      *pending = 0;
      uint8_t md5[16];
      m4d_frame_hash(&frame, md5);
      out->hashes.push_back(HexDigest(md5));
      m4d_frame_unref(&frame);
      start = Clock::now();  // hashing is not decoding
    }
  };
  int r = m4d_send_packet(ctx, data, size);
  if (r == M4D_ERR_AGAIN) {
    drain();
    r = m4d_send_packet(ctx, data, size);
  }
  drain();
  *pending += std::chrono::duration<double>(Clock::now() - start).count();
  return r;
}

}  // namespace

Status DecodeStream(const std::vector<uint8_t>& stream, DecodedStream* decoded) {
  *decoded = DecodedStream();
  M4dSettings settings;
  m4d_default_settings(&settings);
  M4dContext* ctx = nullptr;
  if (m4d_open(&ctx, &settings) < 0) return Status(M4D_ERR_NOMEM, "decoder: open failed");
  size_t offset = 0;
  int error = 0;
  double pending = 0;
  while (offset < stream.size() && error >= 0) {
    M4dPacketInfo info;
    error = m4d_parse_packet_header(stream.data() + offset, stream.size() - offset, &info);
    if (error < 0) break;
    error = SendAndDrain(ctx, stream.data() + offset, info.packet_size, &pending, decoded);
    offset += info.packet_size;
  }
  m4d_close(&ctx);
  if (error < 0)
    return Status(M4D_ERR_BITSTREAM, std::string("decoder: ") + m4d_error_string(error));
  return Status::Ok();
}

Status CheckDecodedHashes(const std::vector<uint8_t>& stream, const SequenceReport& report) {
  DecodedStream decoded;
  const Status s = DecodeStream(stream, &decoded);
  if (!s.ok()) return Status(s.code(), "decoder check: " + s.message());
  const std::vector<std::string>& hashes = decoded.hashes;
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
