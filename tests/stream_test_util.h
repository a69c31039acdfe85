// Helpers for stream-level tests: synthetic streams from the reference writer, splitting
// into packets, and editing packets with their CRCs fixed so that the edit reaches the parser.
#ifndef M4D_TESTS_STREAM_TEST_UTIL_H_
#define M4D_TESTS_STREAM_TEST_UTIL_H_

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/byte_reader.h"
#include "common/crc32.h"
#include "common/md5.h"
#include "decode/frame_hash.h"
#include "m4d/m4d.h"
#include "stream/stream_writer.h"
#include "stream/synthetic_content.h"

namespace m4d {
namespace testing {

using Packet = std::vector<uint8_t>;

struct TestStream {
  std::vector<Packet> packets;
  std::vector<std::string> recon_hashes;  // the writer's closed-loop reconstruction, per frame
  std::vector<size_t> dynamic_counts;     // |D| per frame
};

struct TestStreamShape {
  int gops = 3;
  int frames_per_gop = 4;
  int static_count = 1500;
  int dynamic_count = 400;
  int sh_degree = 1;
  uint64_t seed = 5;
  // GOPs after the first are dependent (bitstream 0.3). Each replaces every
  // static_change_step-th static Gaussian and adds 5 more with a STATIC_UPDATE (0: none).
  bool dependent_gops = false;
  int static_change_step = 0;
  // Inter frames change the dynamic set's colours with an APPEARANCE (bitstream 0.3).
  bool appearance = false;
  int version_minor = M4D_BITSTREAM_VERSION_MINOR;
};

// A dependent keyframe's static change of MakeTestStream.
inline SetChange TestStaticChange(const GaussianSet& static_set, const TestStreamShape& shape,
                                  uint64_t seed) {
  SetChange change;
  change.removed.assign(static_set.size(), 0);
  size_t removed = 0;
  for (int i = 0; shape.static_change_step > 0 && i < static_cast<int>(static_set.size());
       i += shape.static_change_step, ++removed) {
    change.removed[static_cast<size_t>(i)] = 1;
  }
  const float center[3] = {1, 0, 0};
  change.added = SyntheticGaussianSet(shape.static_change_step > 0 ? removed + 5 : 0,
                                      shape.sh_degree, seed, center, 1.0f);
  return change;
}

inline std::vector<Packet> SplitPackets(const std::vector<uint8_t>& bytes) {
  std::vector<Packet> packets;
  size_t pos = 0;
  while (pos < bytes.size()) {
    M4dPacketInfo info;
    if (m4d_parse_packet_header(&bytes[pos], bytes.size() - pos, &info) != M4D_OK) break;
    packets.emplace_back(bytes.begin() + pos, bytes.begin() + pos + info.packet_size);
    pos += info.packet_size;
  }
  return packets;
}

constexpr float kTestAppearanceStep = 0.0123f;

// APPEARANCE values for a set of n: every third Gaussian changes, by -7..7 steps.
inline std::vector<int32_t> TestAppearanceValues(size_t n, int frame) {
  std::vector<int32_t> values(3 * n, 0);
  for (size_t i = static_cast<size_t>(frame) % 3; i < n; i += 3) {
    for (int c = 0; c < 3; ++c) values[3 * i + c] = static_cast<int32_t>((i + 5 * c) % 15) - 7;
  }
  return values;
}

inline TestStream MakeTestStream(const TestStreamShape& shape = TestStreamShape()) {
  StreamWriterOptions options;
  options.sequence.sh_degree = shape.sh_degree;
  options.sequence.version_minor = shape.version_minor;
  options.sequence.grid.resolution[0] = 8;
  options.sequence.grid.resolution[1] = 12;
  options.sequence.grid.resolution[2] = 20;
  options.sequence.mlp.hidden_width = 16;
  StreamWriter writer(options);
  TestStream out;
  const float center[3] = {0, 0, 0}, fg_center[3] = {0.1f, 0.2f, -0.1f};
  for (int g = 0; g < shape.gops; ++g) {
    const uint64_t seed = shape.seed * 100 + g;
    DecodedFrame recon;
    const GaussianSet dynamic_set =
        SyntheticGaussianSet(shape.dynamic_count, shape.sh_degree, seed + 1, fg_center, 0.4f);
    const MlpWeights mlp =
        SyntheticMlp(options.sequence.grid.feature_count(), options.sequence.mlp, seed);
    Status status =
        g > 0 && shape.dependent_gops
            ? writer.WriteDependentKeyframe(TestStaticChange(writer.static_set(), shape, seed * 3),
                                            dynamic_set, mlp, &recon)
            : writer.WriteKeyframe(
                  SyntheticGaussianSet(shape.static_count, shape.sh_degree, seed, center, 2.0f),
                  dynamic_set, mlp, &recon);
    if (!status.ok()) throw std::runtime_error(status.message());
    out.recon_hashes.push_back(FrameHashHex(recon));
    out.dynamic_counts.push_back(recon.dynamic_layer->size());
    for (int f = 1; f < shape.frames_per_gop; ++f) {
      status = writer.WriteMotion(
          SyntheticMotionGrid(options.sequence.grid, seed * 7 + f, -0.6f, 0.6f, 0.2f));
      if (!status.ok()) throw std::runtime_error(status.message());
      const size_t n = writer.moved_dynamic_set().size();
      if (shape.appearance) {
        status = writer.WriteAppearance(kTestAppearanceStep, TestAppearanceValues(n, f));
        if (!status.ok()) throw std::runtime_error(status.message());
      }
      std::vector<uint8_t> removed(n, 0);
      for (size_t i = static_cast<size_t>(f); i < n; i += 37) removed[i] = 1;
      status = writer.WriteCompensation(
          removed, SyntheticGaussianSet(20 + f, shape.sh_degree, seed * 13 + f, fg_center, 0.4f),
          &recon);
      if (!status.ok()) throw std::runtime_error(status.message());
      out.recon_hashes.push_back(FrameHashHex(recon));
      out.dynamic_counts.push_back(recon.dynamic_layer->size());
    }
  }
  out.packets = SplitPackets(writer.bytes());
  return out;
}

// Recomputes the payload CRC and the header CRC of a packet after an edit.
inline void FixCrcs(Packet* p) {
  const uint32_t payload_crc = Crc32(p->data() + 24, p->size() - 24);
  for (int i = 0; i < 4; ++i) (*p)[16 + i] = static_cast<uint8_t>(payload_crc >> (8 * i));
  const uint32_t header_crc = Crc32(p->data(), 20);
  for (int i = 0; i < 4; ++i) (*p)[20 + i] = static_cast<uint8_t>(header_crc >> (8 * i));
}

// Sets payload_size to the actual payload length (after resizing a payload).
inline void FixPayloadSize(Packet* p) {
  const uint32_t size = static_cast<uint32_t>(p->size() - 24);
  for (int i = 0; i < 4; ++i) (*p)[12 + i] = static_cast<uint8_t>(size >> (8 * i));
  FixCrcs(p);
}

inline std::string HashOf(const M4dFrame& frame) {
  uint8_t md5[16];
  m4d_frame_hash(&frame, md5);
  return HexDigest(md5);
}

// Decodes packets with the C API; returns the frames' hashes and the send results.
struct DecodeResult {
  std::vector<std::string> hashes;
  std::vector<uint32_t> frame_indices;
  std::vector<int> errors;  // non-zero send results other than AGAIN
};

inline DecodeResult DecodePackets(M4dContext* ctx, const std::vector<Packet>& packets) {
  DecodeResult result;
  auto drain = [&]() {
    M4dFrame frame;
    while (m4d_get_frame(ctx, &frame) == M4D_OK) {
      result.hashes.push_back(HashOf(frame));
      result.frame_indices.push_back(frame.frame_index);
      m4d_frame_unref(&frame);
    }
  };
  for (const Packet& p : packets) {
    int r = m4d_send_packet(ctx, p.data(), p.size());
    if (r == M4D_ERR_AGAIN) {
      drain();
      r = m4d_send_packet(ctx, p.data(), p.size());
    }
    if (r < 0) result.errors.push_back(r);
    drain();
  }
  return result;
}

inline DecodeResult DecodeWith(const M4dSettings& settings, const std::vector<Packet>& packets) {
  M4dContext* ctx = nullptr;
  if (m4d_open(&ctx, &settings) != M4D_OK) throw std::runtime_error("m4d_open failed");
  DecodeResult result = DecodePackets(ctx, packets);
  m4d_close(&ctx);
  return result;
}

// A byte stream read the way a player reads a file (bitstream-spec 3): parse a header, send
// the packet; after a damaged header flush the decoder and resynchronise on the next header
// (bytes were skipped), after a failed send resynchronise right after the packet's header.
struct PlayResult {
  std::vector<std::pair<uint32_t, std::string>> frames;  // (frame_index, hash) in output order
  std::vector<uint32_t> concealed;                       // M4dFrame.concealed_layers of each frame
  std::vector<int> errors;                               // header and send errors, in order
  bool truncated = false;  // the data ends inside a packet or a frame (spec 9, TRUNCATED)
  size_t steps = 0;        // loop iterations (each moves forward)
};

inline PlayResult PlayBytes(const M4dSettings& settings, const std::vector<uint8_t>& bytes) {
  PlayResult out;
  M4dContext* ctx = nullptr;
  if (m4d_open(&ctx, &settings) != M4D_OK) throw std::runtime_error("m4d_open failed");
  auto drain = [&]() {
    M4dFrame frame;
    while (m4d_get_frame(ctx, &frame) == M4D_OK) {
      out.frames.emplace_back(frame.frame_index, HashOf(frame));
      out.concealed.push_back(frame.concealed_layers);
      m4d_frame_unref(&frame);
    }
  };
  auto resync = [&](size_t from) {
    size_t offset = 0;
    M4dPacketInfo info;
    const int r = m4d_find_packet(bytes.data() + from, bytes.size() - from, &offset, &info);
    return r == M4D_OK || info.packet_size > 0 ? from + offset : bytes.size();
  };
  size_t pos = 0;
  bool inside_frame = false;  // the last header read has no end_of_frame
  while (pos < bytes.size()) {
    ++out.steps;
    M4dPacketInfo info;
    const int parsed = m4d_parse_packet_header(&bytes[pos], bytes.size() - pos, &info);
    if (parsed == M4D_ERR_AGAIN) {
      out.truncated = true;
      inside_frame = false;
      break;
    }
    if (parsed < 0) {
      out.errors.push_back(parsed);
      m4d_flush(ctx);
      pos = resync(pos + 1);
      continue;
    }
    inside_frame = !info.end_of_frame;
    int r = m4d_send_packet(ctx, &bytes[pos], info.packet_size);
    if (r == M4D_ERR_AGAIN) {
      drain();
      r = m4d_send_packet(ctx, &bytes[pos], info.packet_size);
    }
    drain();
    if (r < 0) {
      out.errors.push_back(r);
      pos = resync(pos + 24);
      continue;
    }
    pos += info.packet_size;
  }
  out.truncated = out.truncated || inside_frame;
  m4d_close(&ctx);
  return out;
}

inline M4dSettings DefaultSettings() {
  M4dSettings s;
  m4d_default_settings(&s);
  return s;
}

}  // namespace testing
}  // namespace m4d

#endif  // M4D_TESTS_STREAM_TEST_UTIL_H_
