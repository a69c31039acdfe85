// Helpers for stream-level tests that need the decoder only: packets of a byte stream, the
// committed conformance streams, editing packets with their CRCs fixed so that an edit
// reaches the parser, and decoding with the C API.
#ifndef M4D_TESTS_SDK_PACKET_TEST_UTIL_H_
#define M4D_TESTS_SDK_PACKET_TEST_UTIL_H_

#include <cstdint>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "m4d/m4d.h"
#include "sdk/src/common/crc32.h"
#include "sdk/src/common/md5.h"

namespace m4d {
namespace testing {

using Packet = std::vector<uint8_t>;

struct TestStream {
  std::vector<Packet> packets;
  std::vector<std::string> recon_hashes;  // the writer's closed-loop reconstruction, per frame
  std::vector<size_t> dynamic_counts;     // |D| per frame
};

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

// conformance/streams/<name>.m4d as packets, with the expected hashes of its frames (all
// layers) as the reconstruction's.
inline TestStream LoadConformanceStream(const std::string& name) {
  const std::string base = std::string(M4D_SOURCE_DIR) + "/conformance/streams/" + name;
  std::ifstream file(base + ".m4d", std::ios::binary);
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)),
                                   std::istreambuf_iterator<char>());
  if (bytes.empty()) throw std::runtime_error("no conformance stream " + base + ".m4d");
  TestStream out;
  out.packets = SplitPackets(bytes);
  std::ifstream hashes(base + ".md5");
  uint32_t frame = 0;
  for (std::string hash; hashes >> frame >> hash;) out.recon_hashes.push_back(hash);
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

#endif  // M4D_TESTS_SDK_PACKET_TEST_UTIL_H_
