// What the public API tells about a stream and lets a player do with it: stream information,
// props passed through with packets, seeking to a frame, and decoder threads.
#include <gtest/gtest.h>

#include <climits>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tests/encoder/stream_test_util.h"

namespace m4d {
namespace testing {
namespace {

// Three GOPs of four frames; more dynamic Gaussians than one motion task holds (4096).
TestStream ThreeGops(bool dependent) {
  TestStreamShape shape;
  shape.gops = 3;
  shape.frames_per_gop = 4;
  shape.static_count = 500;
  shape.dynamic_count = 9000;
  shape.dependent_gops = dependent;
  shape.static_change_step = dependent ? 7 : 0;
  return MakeTestStream(shape);
}

std::vector<uint8_t> Concatenate(const std::vector<Packet>& packets) {
  std::vector<uint8_t> bytes;
  for (const Packet& p : packets) bytes.insert(bytes.end(), p.begin(), p.end());
  return bytes;
}

TEST(StreamInfo, FollowsTheConfigurationAndTheGops) {
  for (bool dependent : {false, true}) {
    const TestStream stream = ThreeGops(dependent);
    M4dSettings s = DefaultSettings();
    M4dContext* ctx = nullptr;
    ASSERT_EQ(m4d_open(&ctx, &s), M4D_OK);
    M4dStreamInfo info;
    std::memset(&info, 0xff, sizeof(info));
    EXPECT_EQ(m4d_get_stream_info(ctx, &info), M4D_ERR_AGAIN);
    EXPECT_EQ(info.fps_num, 0u);  // zeroed
    const DecodeResult result = DecodePackets(ctx, stream.packets);
    ASSERT_EQ(result.hashes, stream.recon_hashes);
    ASSERT_EQ(m4d_get_stream_info(ctx, &info), M4D_OK);
    EXPECT_EQ(info.bitstream_major, 0u);
    EXPECT_EQ(info.bitstream_minor, static_cast<uint32_t>(M4D_BITSTREAM_VERSION_MINOR));
    EXPECT_EQ(info.sh_degree, 1u);
    EXPECT_EQ(info.fps_num, 30u);
    EXPECT_EQ(info.fps_den, 1u);
    EXPECT_EQ(info.layers_coded, M4D_LAYER_ALL);
    EXPECT_EQ(info.frames_decoded, 12u);
    EXPECT_EQ(info.gops, 3u);
    EXPECT_EQ(info.random_access_gops, dependent ? 1u : 3u);
    EXPECT_EQ(info.last_keyframe_index, 8u);
    EXPECT_EQ(info.last_random_access_index, dependent ? 0u : 8u);
    // A flush (a seek) keeps what was seen.
    m4d_flush(ctx);
    ASSERT_EQ(m4d_get_stream_info(ctx, &info), M4D_OK);
    EXPECT_EQ(info.gops, 3u);
    EXPECT_EQ(m4d_get_stream_info(nullptr, &info), M4D_ERR_INVALID_ARG);
    EXPECT_EQ(m4d_get_stream_info(ctx, nullptr), M4D_ERR_INVALID_ARG);
    m4d_close(&ctx);
  }
}

TEST(StreamInfo, PropsComeBackWithTheFrameTheirPacketCompletes) {
  const TestStream stream = ThreeGops(true);
  M4dSettings s = DefaultSettings();
  M4dContext* ctx = nullptr;
  ASSERT_EQ(m4d_open(&ctx, &s), M4D_OK);
  std::vector<int64_t> timestamps;  // per output frame
  std::vector<const void*> user_data;
  auto drain = [&]() {
    M4dFrame frame;
    while (m4d_get_frame(ctx, &frame) == M4D_OK) {
      timestamps.push_back(frame.props.timestamp);
      user_data.push_back(frame.props.user_data);
      m4d_frame_unref(&frame);
    }
  };
  std::vector<int64_t> expected;
  for (size_t i = 0; i < stream.packets.size(); ++i) {
    const Packet& p = stream.packets[i];
    M4dDataProps props;
    m4d_default_data_props(&props);
    props.timestamp = 1000 + static_cast<int64_t>(i);
    props.user_data = const_cast<Packet*>(&p);
    // The odd frames' last packets go without props: their frames get the defaults.
    const bool with_props = expected.size() % 2 == 0;
    ASSERT_EQ(m4d_send_packet_props(ctx, p.data(), p.size(), with_props ? &props : nullptr),
              M4D_OK);
    M4dPacketInfo info;
    ASSERT_EQ(m4d_parse_packet_header(p.data(), p.size(), &info), M4D_OK);
    if (info.end_of_frame) expected.push_back(with_props ? props.timestamp : INT64_MIN);
    drain();
  }
  ASSERT_EQ(timestamps, expected);
  for (size_t f = 0; f < user_data.size(); ++f) {
    EXPECT_EQ(user_data[f] == nullptr, f % 2 == 1) << "frame " << f;
  }
  m4d_close(&ctx);
}

// Props' reserved bytes are refused as the settings' are, and the packet is not consumed.
TEST(StreamInfo, PropsWithNonZeroReservedBytesAreRefused) {
  const TestStream stream = ThreeGops(false);
  M4dSettings s = DefaultSettings();
  M4dContext* ctx = nullptr;
  ASSERT_EQ(m4d_open(&ctx, &s), M4D_OK);
  M4dDataProps props;
  m4d_default_data_props(&props);
  props.reserved[7] = 1;
  const Packet& header = stream.packets[0];
  EXPECT_EQ(m4d_send_packet_props(ctx, header.data(), header.size(), &props), M4D_ERR_INVALID_ARG);
  EXPECT_STRNE(m4d_last_error(ctx), "");
  props.reserved[7] = 0;
  for (size_t i = 0; i < 4; ++i) {
    const Packet& p = stream.packets[i];
    ASSERT_EQ(m4d_send_packet_props(ctx, p.data(), p.size(), &props), M4D_OK) << i;
  }
  M4dFrame frame;
  ASSERT_EQ(m4d_get_frame(ctx, &frame), M4D_OK);
  EXPECT_EQ(frame.frame_index, 0u);
  m4d_frame_unref(&frame);
  m4d_close(&ctx);
}

TEST(StreamInfo, FindRandomAccessSeeksToAnyFrame) {
  const TestStream stream = ThreeGops(false);
  const std::vector<uint8_t> bytes = Concatenate(stream.packets);
  for (uint32_t f = 0; f < 12; ++f) {
    size_t offset = 1;
    uint32_t first = 99;
    ASSERT_EQ(m4d_find_random_access(bytes.data(), bytes.size(), f, &offset, &first), M4D_OK);
    EXPECT_EQ(first, f / 4 * 4) << "frame " << f;
    M4dPacketInfo info;
    ASSERT_EQ(m4d_parse_packet_header(&bytes[offset], bytes.size() - offset, &info), M4D_OK);
    EXPECT_EQ(info.type, static_cast<uint32_t>(M4D_PACKET_SEQUENCE_HEADER));
    EXPECT_EQ(info.frame_index, first);
    // Decoding from there gives the frame as decoding from the start does.
    const PlayResult played =
        PlayBytes(DefaultSettings(),
                  std::vector<uint8_t>(bytes.begin() + static_cast<long>(offset), bytes.end()));
    ASSERT_FALSE(played.frames.empty());
    EXPECT_EQ(played.frames[f - first].first, f);
    EXPECT_EQ(played.frames[f - first].second, stream.recon_hashes[f]);
  }
  size_t offset = 0;
  uint32_t first = 0;
  EXPECT_EQ(m4d_find_random_access(bytes.data(), bytes.size(), 12, &offset, &first), M4D_ERR_AGAIN);
  // Without the first SEQUENCE_HEADER, frames 0..3 have no random-access point before them.
  const size_t cut = stream.packets[0].size();
  EXPECT_EQ(m4d_find_random_access(bytes.data() + cut, bytes.size() - cut, 2, &offset, &first),
            M4D_ERR_BITSTREAM);
  ASSERT_EQ(m4d_find_random_access(bytes.data() + cut, bytes.size() - cut, 5, &offset, &first),
            M4D_OK);
  EXPECT_EQ(first, 4u);
  EXPECT_EQ(m4d_find_random_access(nullptr, 0, 0, &offset, &first), M4D_ERR_INVALID_ARG);
}

// Frame numbers that wrap at 2^32 (2^32 - 2, 2^32 - 1, 0 | 1, 2, 3): each frame's own GOP.
TEST(StreamInfo, FindRandomAccessAcrossTheFrameIndexWrap) {
  std::ifstream file(
      std::string(M4D_SOURCE_DIR) + "/conformance/streams/edit_frame_index_wraps.m4d",
      std::ios::binary);
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)),
                                   std::istreambuf_iterator<char>());
  ASSERT_FALSE(bytes.empty());
  const uint32_t frames[] = {0xfffffffeu, 0xffffffffu, 0, 1, 2, 3};
  for (int i = 0; i < 6; ++i) {
    size_t offset = 0;
    uint32_t first = 0;
    ASSERT_EQ(m4d_find_random_access(bytes.data(), bytes.size(), frames[i], &offset, &first),
              M4D_OK);
    EXPECT_EQ(first, frames[i / 3 * 3]) << frames[i];
    EXPECT_EQ(offset == 0, i < 3) << frames[i];
  }
}

TEST(StreamInfo, DependentGopsSeekToTheirRandomAccessPoint) {
  const TestStream stream = ThreeGops(true);
  const std::vector<uint8_t> bytes = Concatenate(stream.packets);
  size_t offset = 1;
  uint32_t first = 99;
  ASSERT_EQ(m4d_find_random_access(bytes.data(), bytes.size(), 9, &offset, &first), M4D_OK);
  EXPECT_EQ(offset, 0u);
  EXPECT_EQ(first, 0u);
}

TEST(StreamInfo, EveryThreadCountDecodesTheSameFrames) {
  const TestStream stream = ThreeGops(true);
  for (int threads : {1, 2, 0, 3}) {
    M4dSettings s = DefaultSettings();
    s.threads = threads;
    EXPECT_EQ(DecodeWith(s, stream.packets).hashes, stream.recon_hashes) << threads << " threads";
  }
  M4dContext* ctx = nullptr;
  for (int bad : {-1, 257}) {
    M4dSettings s = DefaultSettings();
    s.threads = bad;
    EXPECT_EQ(m4d_open(&ctx, &s), M4D_ERR_INVALID_ARG) << bad;
    EXPECT_EQ(ctx, nullptr);
  }
}

// What the library fills comes back with its reserved bytes zero, whatever the caller's
// memory held, so that later versions can give them a meaning.
TEST(StreamInfo, ReservedBytesComeBackZero) {
  const TestStream stream = ThreeGops(false);
  auto all_zero = [](const uint8_t* bytes, size_t n) {
    for (size_t i = 0; i < n; ++i) {
      if (bytes[i] != 0) return false;
    }
    return true;
  };
  M4dPacketInfo info;
  std::memset(&info, 0xab, sizeof(info));
  ASSERT_EQ(m4d_parse_packet_header(stream.packets[0].data(), stream.packets[0].size(), &info),
            M4D_OK);
  EXPECT_TRUE(all_zero(info.reserved, sizeof(info.reserved)));
  M4dSettings s = DefaultSettings();
  M4dContext* ctx = nullptr;
  ASSERT_EQ(m4d_open(&ctx, &s), M4D_OK);
  for (size_t i = 0; i < 4; ++i) {
    ASSERT_EQ(m4d_send_packet(ctx, stream.packets[i].data(), stream.packets[i].size()), M4D_OK);
  }
  M4dFrame frame;
  std::memset(&frame, 0xab, sizeof(frame));
  ASSERT_EQ(m4d_get_frame(ctx, &frame), M4D_OK);
  EXPECT_TRUE(all_zero(frame.reserved, sizeof(frame.reserved)));
  EXPECT_TRUE(all_zero(frame.static_layer.reserved, sizeof(frame.static_layer.reserved)));
  EXPECT_TRUE(all_zero(frame.dynamic_layer.reserved, sizeof(frame.dynamic_layer.reserved)));
  EXPECT_TRUE(all_zero(frame.props.reserved, sizeof(frame.props.reserved)));
  m4d_frame_unref(&frame);
  M4dStreamInfo stream_info;
  std::memset(&stream_info, 0xab, sizeof(stream_info));
  ASSERT_EQ(m4d_get_stream_info(ctx, &stream_info), M4D_OK);
  EXPECT_TRUE(all_zero(stream_info.reserved, sizeof(stream_info.reserved)));
  m4d_close(&ctx);
}

TEST(StreamInfo, DefaultsAreDocumented) {
  M4dSettings s;
  std::memset(&s, 0xff, sizeof(s));
  m4d_default_settings(&s);
  EXPECT_EQ(s.threads, 1);
  M4dDataProps props;
  std::memset(&props, 0xff, sizeof(props));
  m4d_default_data_props(&props);
  EXPECT_EQ(props.timestamp, INT64_MIN);
  EXPECT_EQ(props.duration, 0);
  EXPECT_EQ(props.offset, -1);
  EXPECT_EQ(props.user_data, nullptr);
  for (uint8_t b : props.reserved) EXPECT_EQ(b, 0);
}

}  // namespace
}  // namespace testing
}  // namespace m4d
