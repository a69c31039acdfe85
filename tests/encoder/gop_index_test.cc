// The GOP index (encoder/src/stream/gop_index.h) on conformance streams: its GOPs cover the stream
// without gaps, start where the decoder's keyframes start (the first packet of each keyframe, as
// m4d_probe lists packets), carry the random-access flags of those keyframes, and a damaged or
// truncated stream is an error with a message, not an index.
#include "encoder/src/stream/gop_index.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "m4d/m4d.h"

namespace m4d {
namespace {

std::vector<uint8_t> ReadStream(const std::string& relative) {
  std::ifstream in(std::string(M4D_SOURCE_DIR) + "/conformance/" + relative, std::ios::binary);
  return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)),
                              std::istreambuf_iterator<char>());
}

struct DecodedFrame {
  uint32_t index = 0;
  bool keyframe = false;
  bool random_access = false;  // its packets include a SEQUENCE_HEADER
  size_t first_packet = 0;     // byte offset of its first packet
};

// Every frame as the decoder outputs it, with the offset of its first packet, as m4d_probe
// attributes packets to frames (an undamaged stream: one frame per end_of_frame).
std::vector<DecodedFrame> DecodeFrames(const std::vector<uint8_t>& data) {
  M4dSettings settings;
  m4d_default_settings(&settings);
  M4dContext* ctx = nullptr;
  EXPECT_EQ(m4d_open(&ctx, &settings), M4D_OK);
  std::vector<DecodedFrame> frames;
  DecodedFrame pending;
  bool inside = false;
  auto take = [&]() {
    M4dFrame frame;
    while (m4d_get_frame(ctx, &frame) == M4D_OK) {
      EXPECT_FALSE(inside) << "a frame came out before its last packet";
      frames.push_back(pending);
      frames.back().index = frame.frame_index;
      frames.back().keyframe = frame.is_keyframe != 0;
      m4d_frame_unref(&frame);
    }
  };
  for (size_t pos = 0; pos < data.size();) {
    M4dPacketInfo info;
    if (m4d_parse_packet_header(&data[pos], data.size() - pos, &info) != M4D_OK) {
      ADD_FAILURE() << "damaged header at byte " << pos;
      break;
    }
    if (!inside) pending = DecodedFrame{0, false, false, pos};
    inside = !info.end_of_frame;
    pending.random_access = pending.random_access || info.type == M4D_PACKET_SEQUENCE_HEADER;
    int r = m4d_send_packet(ctx, &data[pos], info.packet_size);
    if (r == M4D_ERR_AGAIN) {
      take();
      r = m4d_send_packet(ctx, &data[pos], info.packet_size);
    }
    EXPECT_EQ(r, M4D_OK) << "byte " << pos;
    take();
    pos += info.packet_size;
  }
  m4d_close(&ctx);
  return frames;
}

void ExpectIndexMatchesDecoder(const std::string& name) {
  SCOPED_TRACE(name);
  const std::vector<uint8_t> data = ReadStream("streams/" + name);
  ASSERT_FALSE(data.empty());
  GopIndex index;
  const Status status = BuildGopIndex(data.data(), data.size(), &index);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(index.stream_bytes, data.size());
  EXPECT_EQ(index.fps, 30.0);

  // Without gaps: each GOP starts where the one before ends, the last ends with the stream.
  ASSERT_FALSE(index.gops.empty());
  uint64_t next_offset = 0;
  int64_t frames = 0;
  for (const GopEntry& gop : index.gops) {
    EXPECT_EQ(gop.offset, next_offset);
    EXPECT_GT(gop.bytes, 0u);
    EXPECT_GT(gop.frames, 0);
    next_offset = gop.offset + gop.bytes;
    frames += gop.frames;
  }
  EXPECT_EQ(next_offset, data.size());
  EXPECT_EQ(frames, index.frames);

  // One GOP per keyframe the decoder outputs, at its first packet, with its flag and frames.
  const std::vector<DecodedFrame> decoded = DecodeFrames(data);
  ASSERT_EQ(static_cast<int64_t>(decoded.size()), index.frames);
  size_t gop = 0;
  for (size_t i = 0; i < decoded.size(); ++i) {
    if (!decoded[i].keyframe) continue;
    ASSERT_LT(gop, index.gops.size());
    const GopEntry& entry = index.gops[gop++];
    EXPECT_EQ(entry.frame, decoded[i].index);
    EXPECT_EQ(entry.offset, decoded[i].first_packet);
    EXPECT_EQ(entry.random_access, decoded[i].random_access);
    size_t end = i + 1;
    while (end < decoded.size() && !decoded[end].keyframe) ++end;
    EXPECT_EQ(entry.frames, static_cast<int64_t>(end - i));
  }
  EXPECT_EQ(gop, index.gops.size());
}

TEST(GopIndexTest, RandomAccessGopsCoverTheStream) {
  ExpectIndexMatchesDecoder("synth_sh3_three_gops.m4d");
}

TEST(GopIndexTest, DependentGopsAreNotRandomAccess) {
  ExpectIndexMatchesDecoder("synth_sh1_dependent_gops.m4d");
  const std::vector<uint8_t> data = ReadStream("streams/synth_sh1_dependent_gops.m4d");
  GopIndex index;
  ASSERT_TRUE(BuildGopIndex(data.data(), data.size(), &index).ok());
  ASSERT_GE(index.gops.size(), 2u);
  EXPECT_TRUE(index.gops[0].random_access);
  EXPECT_FALSE(index.gops[1].random_access);
}

TEST(GopIndexTest, JsonHoldsTheContractFields) {
  const std::vector<uint8_t> data = ReadStream("streams/enc_adaptive_gop.m4d");
  GopIndex index;
  ASSERT_TRUE(BuildGopIndex(data.data(), data.size(), &index).ok());
  const nlohmann::json json = nlohmann::json::parse(GopIndexJson(index));
  EXPECT_EQ(json["format"], "m4d-gop-index");
  EXPECT_EQ(json["version"], 1);
  EXPECT_EQ(json["stream_bytes"], data.size());
  EXPECT_EQ(json["frames"], index.frames);
  EXPECT_EQ(json["fps"], 30.0);
  ASSERT_EQ(json["gops"].size(), index.gops.size());
  for (size_t i = 0; i < index.gops.size(); ++i) {
    EXPECT_EQ(json["gops"][i]["frame"], index.gops[i].frame);
    EXPECT_EQ(json["gops"][i]["frames"], index.gops[i].frames);
    EXPECT_EQ(json["gops"][i]["offset"], index.gops[i].offset);
    EXPECT_EQ(json["gops"][i]["bytes"], index.gops[i].bytes);
    EXPECT_EQ(json["gops"][i]["random_access"], index.gops[i].random_access);
  }
}

TEST(GopIndexTest, DamagedOrTruncatedStreamIsAnError) {
  struct Case {
    std::string file, message;
  };
  for (const Case& c : {Case{"invalid/bad_payload_crc.m4d", "payload CRC mismatch"},
                        Case{"invalid/truncated_in_payload.m4d", "truncated"},
                        Case{"invalid/bad_header_crc.m4d", "damaged packet header"}}) {
    SCOPED_TRACE(c.file);
    const std::vector<uint8_t> data = ReadStream(c.file);
    ASSERT_FALSE(data.empty());
    GopIndex index;
    const Status status = BuildGopIndex(data.data(), data.size(), &index);
    EXPECT_FALSE(status.ok());
    EXPECT_NE(status.message().find(c.message), std::string::npos) << status.message();
    EXPECT_NE(status.message().find("byte "), std::string::npos) << status.message();
    EXPECT_TRUE(index.gops.empty());
  }
  // A stream cut at a packet boundary inside a frame, and one that starts at a dependent GOP.
  const std::vector<uint8_t> whole = ReadStream("streams/synth_sh1_dependent_gops.m4d");
  GopIndex index;
  ASSERT_TRUE(BuildGopIndex(whole.data(), whole.size(), &index).ok());
  M4dPacketInfo info;
  ASSERT_EQ(m4d_parse_packet_header(whole.data(), whole.size(), &info), M4D_OK);
  const Status cut = BuildGopIndex(whole.data(), info.packet_size, &index);
  EXPECT_FALSE(cut.ok());
  EXPECT_NE(cut.message().find("ends inside a frame"), std::string::npos) << cut.message();
  GopIndex full;
  ASSERT_TRUE(BuildGopIndex(whole.data(), whole.size(), &full).ok());
  const GopEntry& dependent = full.gops[1];
  const Status tail =
      BuildGopIndex(whole.data() + dependent.offset, whole.size() - dependent.offset, &index);
  EXPECT_FALSE(tail.ok());
  EXPECT_FALSE(BuildGopIndex(whole.data(), 0, &index).ok());
}

}  // namespace
}  // namespace m4d
