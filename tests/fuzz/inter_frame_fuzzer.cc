// libFuzzer target for the inter-frame layer decoders in context: a real keyframe and motion
// grid are decoded first, then the input is the payload of frame 1's MOTION_GRID (first byte
// even) or COMPENSATION (odd), sent with valid CRCs so that it reaches the parsers, the motion
// application and the compensation merge.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "bitstream/packet_header.h"
#include "stream_test_util.h"

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
  const bool motion = (data[0] & 1) == 0;
  std::vector<m4d::testing::Packet> packets(Prefix().begin(), Prefix().begin() + (motion ? 4 : 5));
  packets.emplace_back();
  m4d::AppendPacket(motion ? M4D_PACKET_MOTION_GRID : M4D_PACKET_COMPENSATION, 1, !motion, data + 1,
                    size - 1, &packets.back());
  if (motion) packets.push_back(Prefix()[5]);
  m4d::testing::DecodeWith(m4d::testing::DefaultSettings(), packets);
  return 0;
}
