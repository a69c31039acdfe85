// libFuzzer target for the set-changing layer decoders in context: a real keyframe and motion
// grid are decoded first, then the input is the payload of frame 1's MOTION_GRID (first byte
// 0 mod 4) or COMPENSATION (1 mod 4), of the STATIC_UPDATE of a dependent keyframe at frame 2
// (2 mod 4, followed by that keyframe's valid KEYFRAME_DYNAMIC and MLP_WEIGHTS), or of an
// APPEARANCE between frame 1's valid MOTION_GRID and COMPENSATION (3 mod 4), sent with valid
// CRCs so that it reaches the parsers, the motion and appearance application and the merges.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "sdk/src/bitstream/packet_header.h"
#include "tests/encoder/stream_test_util.h"

namespace {

const std::vector<m4d::testing::Packet>& Prefix() {
  static const std::vector<m4d::testing::Packet> packets = [] {
    m4d::testing::TestStreamShape shape;
    shape.gops = 1;
    shape.frames_per_gop = 2;
    shape.static_count = 40;
    shape.dynamic_count = 60;
    return m4d::testing::MakeTestStream(shape).packets;  // SEQ KS KD MLP MG COMP
  }();
  return packets;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const int mode = data[0] % 4;
  if (mode == 2) {
    std::vector<m4d::testing::Packet> packets = Prefix();
    for (uint8_t type :
         {M4D_PACKET_STATIC_UPDATE, M4D_PACKET_KEYFRAME_DYNAMIC, M4D_PACKET_MLP_WEIGHTS}) {
      // The dependent keyframe's sets and MLP are the first keyframe's (packets 2 and 3).
      const m4d::testing::Packet& from = Prefix()[type == M4D_PACKET_MLP_WEIGHTS ? 3 : 2];
      const bool fuzzed = type == M4D_PACKET_STATIC_UPDATE;
      packets.emplace_back();
      m4d::AppendPacket(type, 2, type == M4D_PACKET_MLP_WEIGHTS, fuzzed ? data + 1 : &from[24],
                        fuzzed ? size - 1 : from.size() - 24, &packets.back());
    }
    m4d::testing::DecodeWith(m4d::testing::DefaultSettings(), packets);
    return 0;
  }
  if (mode == 3) {
    std::vector<m4d::testing::Packet> packets(Prefix().begin(), Prefix().begin() + 5);
    packets.emplace_back();
    m4d::AppendPacket(M4D_PACKET_APPEARANCE, 1, false, data + 1, size - 1, &packets.back());
    packets.push_back(Prefix()[5]);
    m4d::testing::DecodeWith(m4d::testing::DefaultSettings(), packets);
    return 0;
  }
  const bool motion = mode == 0;
  std::vector<m4d::testing::Packet> packets(Prefix().begin(), Prefix().begin() + (motion ? 4 : 5));
  packets.emplace_back();
  m4d::AppendPacket(motion ? M4D_PACKET_MOTION_GRID : M4D_PACKET_COMPENSATION, 1, !motion, data + 1,
                    size - 1, &packets.back());
  if (motion) packets.push_back(Prefix()[5]);
  m4d::testing::DecodeWith(m4d::testing::DefaultSettings(), packets);
  return 0;
}
