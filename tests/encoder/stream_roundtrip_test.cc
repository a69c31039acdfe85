// Round trips through the reference writer and the SDK's public API: the decoder must
// reproduce the writer's closed-loop reconstruction bit for bit, for every layer choice,
// after seeks, for foreground-only streams and with a caller background.
#include <gtest/gtest.h>

#include <cstring>

#include "tests/encoder/stream_test_util.h"

namespace m4d {
namespace testing {
namespace {

class StreamRoundTrip : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { stream_ = new TestStream(MakeTestStream()); }
  static void TearDownTestSuite() { delete stream_; }
  static TestStream* stream_;
};
TestStream* StreamRoundTrip::stream_ = nullptr;

// Indices of the packets that start each GOP.
std::vector<size_t> GopStarts(const std::vector<Packet>& packets) {
  std::vector<size_t> starts;
  for (size_t i = 0; i < packets.size(); ++i) {
    if (packets[i][4] == M4D_PACKET_SEQUENCE_HEADER) starts.push_back(i);
  }
  return starts;
}

TEST_F(StreamRoundTrip, FullDecodeMatchesWriterReconstruction) {
  const DecodeResult r = DecodeWith(DefaultSettings(), stream_->packets);
  EXPECT_TRUE(r.errors.empty());
  ASSERT_EQ(r.hashes.size(), 12u);
  EXPECT_EQ(r.hashes, stream_->recon_hashes);
  for (size_t i = 0; i < r.frame_indices.size(); ++i) EXPECT_EQ(r.frame_indices[i], i);
}

TEST_F(StreamRoundTrip, MotionAndCompensationChangeTheDynamicLayer) {
  // Consecutive frames differ (motion moved something) and counts follow the compensation.
  for (size_t i = 1; i < stream_->recon_hashes.size(); ++i) {
    EXPECT_NE(stream_->recon_hashes[i], stream_->recon_hashes[i - 1]) << "frame " << i;
  }
  EXPECT_EQ(stream_->dynamic_counts[0], 400u);
  // Frame 1 removes every 37th Gaussian from index 1 (11 of 400) and adds 21.
  EXPECT_EQ(stream_->dynamic_counts[1], 400u - 11u + 21u);
}

TEST_F(StreamRoundTrip, LayerSelectionOutputsOnlyTheChosenLayer) {
  M4dSettings s = DefaultSettings();
  M4dContext *full = nullptr, *bg_only = nullptr, *fg_only = nullptr;
  ASSERT_EQ(m4d_open(&full, &s), M4D_OK);
  s.layers = M4D_LAYER_STATIC;
  ASSERT_EQ(m4d_open(&bg_only, &s), M4D_OK);
  s.layers = M4D_LAYER_DYNAMIC;
  ASSERT_EQ(m4d_open(&fg_only, &s), M4D_OK);
  int frames = 0;
  for (const Packet& p : stream_->packets) {
    for (M4dContext* c : {full, bg_only, fg_only}) {
      ASSERT_EQ(m4d_send_packet(c, p.data(), p.size()), M4D_OK);
    }
    M4dFrame a, b, c;
    if (m4d_get_frame(full, &a) != M4D_OK) continue;
    ASSERT_EQ(m4d_get_frame(bg_only, &b), M4D_OK);
    ASSERT_EQ(m4d_get_frame(fg_only, &c), M4D_OK);
    ++frames;
    EXPECT_EQ(b.layers, M4D_LAYER_STATIC);
    EXPECT_EQ(c.layers, M4D_LAYER_DYNAMIC);
    EXPECT_EQ(b.dynamic_layer.count, 0u);
    EXPECT_EQ(c.static_layer.count, 0u);
    ASSERT_EQ(b.static_layer.count, a.static_layer.count);
    ASSERT_EQ(c.dynamic_layer.count, a.dynamic_layer.count);
    EXPECT_EQ(0, std::memcmp(b.static_layer.positions, a.static_layer.positions,
                             12 * a.static_layer.count));
    EXPECT_EQ(0, std::memcmp(c.dynamic_layer.positions, a.dynamic_layer.positions,
                             12 * a.dynamic_layer.count));
    EXPECT_EQ(0, std::memcmp(c.dynamic_layer.rotations, a.dynamic_layer.rotations,
                             16 * a.dynamic_layer.count));
    m4d_frame_unref(&a);
    m4d_frame_unref(&b);
    m4d_frame_unref(&c);
  }
  EXPECT_EQ(frames, 12);
  m4d_close(&full);
  m4d_close(&bg_only);
  m4d_close(&fg_only);
}

TEST_F(StreamRoundTrip, SeekWithFlushResumesAtTheNextGop) {
  const std::vector<size_t> gops = GopStarts(stream_->packets);
  ASSERT_EQ(gops.size(), 3u);
  M4dSettings s = DefaultSettings();
  M4dContext* ctx = nullptr;
  ASSERT_EQ(m4d_open(&ctx, &s), M4D_OK);
  // Decode part of GOP 0, then seek to GOP 2.
  std::vector<Packet> head(stream_->packets.begin(), stream_->packets.begin() + 6);
  DecodeResult first = DecodePackets(ctx, head);
  EXPECT_EQ(first.hashes.size(), 2u);
  m4d_flush(ctx);
  std::vector<Packet> tail(stream_->packets.begin() + gops[2], stream_->packets.end());
  DecodeResult second = DecodePackets(ctx, tail);
  EXPECT_TRUE(second.errors.empty());
  ASSERT_EQ(second.hashes.size(), 4u);
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(second.hashes[i], stream_->recon_hashes[8 + i]);

  // Packets sent after a flush but before a SEQUENCE_HEADER are skipped without output.
  m4d_flush(ctx);
  std::vector<Packet> mid(stream_->packets.begin() + gops[1] + 4, stream_->packets.end());
  DecodeResult third = DecodePackets(ctx, mid);
  EXPECT_TRUE(third.errors.empty());
  ASSERT_EQ(third.hashes.size(), 4u);
  EXPECT_EQ(third.hashes.front(), stream_->recon_hashes[8]);
  m4d_close(&ctx);
}

TEST_F(StreamRoundTrip, ForegroundOnlyStreamDecodes) {
  std::vector<Packet> stripped;
  for (const Packet& p : stream_->packets) {
    if (p[4] != M4D_PACKET_KEYFRAME_STATIC) stripped.push_back(p);
  }
  M4dContext *full = nullptr, *fg = nullptr;
  M4dSettings s = DefaultSettings();
  ASSERT_EQ(m4d_open(&full, &s), M4D_OK);
  ASSERT_EQ(m4d_open(&fg, &s), M4D_OK);
  size_t j = 0, frames = 0;
  for (const Packet& p : stripped) {
    while (stream_->packets[j][4] == M4D_PACKET_KEYFRAME_STATIC) {
      ASSERT_EQ(m4d_send_packet(full, stream_->packets[j].data(), stream_->packets[j].size()), 0);
      ++j;
    }
    ASSERT_EQ(m4d_send_packet(full, stream_->packets[j].data(), stream_->packets[j].size()), 0);
    ++j;
    ASSERT_EQ(m4d_send_packet(fg, p.data(), p.size()), M4D_OK);
    M4dFrame a, b;
    if (m4d_get_frame(fg, &b) != M4D_OK) continue;
    ASSERT_EQ(m4d_get_frame(full, &a), M4D_OK);
    ++frames;
    EXPECT_EQ(b.static_layer.count, 0u);
    ASSERT_EQ(b.dynamic_layer.count, a.dynamic_layer.count);
    EXPECT_EQ(0, std::memcmp(b.dynamic_layer.sh, a.dynamic_layer.sh,
                             4 * 3 * a.dynamic_layer.sh_coefficients * a.dynamic_layer.count));
    m4d_frame_unref(&a);
    m4d_frame_unref(&b);
  }
  EXPECT_EQ(frames, 12u);
  m4d_close(&full);
  m4d_close(&fg);
}

TEST_F(StreamRoundTrip, CallerBackgroundReplacesTheStaticLayer) {
  const float center[3] = {5, 5, 5};
  const GaussianSet bg = SyntheticGaussianSet(123, 0, 99, center, 1.0f);
  const M4dGaussians view = GaussianView(bg);
  M4dSettings s = DefaultSettings();
  M4dContext* ctx = nullptr;
  ASSERT_EQ(m4d_open(&ctx, &s), M4D_OK);
  ASSERT_EQ(m4d_set_background(ctx, &view), M4D_OK);
  const DecodeResult with_bg = DecodePackets(ctx, stream_->packets);
  EXPECT_TRUE(with_bg.errors.empty());
  ASSERT_EQ(with_bg.hashes.size(), 12u);
  // The same frames with the stream's own background differ only in the static layer.
  M4dFrame frame;
  ASSERT_EQ(m4d_set_background(ctx, nullptr), M4D_OK);
  m4d_flush(ctx);
  for (size_t i = 0; i < 4; ++i) {
    ASSERT_EQ(m4d_send_packet(ctx, stream_->packets[i].data(), stream_->packets[i].size()), 0);
  }
  ASSERT_EQ(m4d_get_frame(ctx, &frame), M4D_OK);
  EXPECT_EQ(HashOf(frame), stream_->recon_hashes[0]);
  EXPECT_NE(with_bg.hashes[0], stream_->recon_hashes[0]);
  m4d_frame_unref(&frame);

  ASSERT_EQ(m4d_set_background(ctx, &view), M4D_OK);
  m4d_flush(ctx);
  for (size_t i = 0; i < 4; ++i) {
    ASSERT_EQ(m4d_send_packet(ctx, stream_->packets[i].data(), stream_->packets[i].size()), 0);
  }
  ASSERT_EQ(m4d_get_frame(ctx, &frame), M4D_OK);
  ASSERT_EQ(frame.static_layer.count, 123u);
  EXPECT_EQ(frame.static_layer.sh_degree, 0u);
  EXPECT_EQ(0, std::memcmp(frame.static_layer.positions, bg.positions.data(), 12 * 123));
  m4d_frame_unref(&frame);
  m4d_close(&ctx);
}

TEST_F(StreamRoundTrip, FramesStayValidWhileDecodingContinues) {
  M4dSettings s = DefaultSettings();
  M4dContext* ctx = nullptr;
  ASSERT_EQ(m4d_open(&ctx, &s), M4D_OK);
  std::vector<M4dFrame> held;
  for (const Packet& p : stream_->packets) {
    int r = m4d_send_packet(ctx, p.data(), p.size());
    if (r == M4D_ERR_AGAIN) {
      held.emplace_back();
      ASSERT_EQ(m4d_get_frame(ctx, &held.back()), M4D_OK);
      r = m4d_send_packet(ctx, p.data(), p.size());
    }
    ASSERT_EQ(r, M4D_OK);
  }
  held.emplace_back();
  ASSERT_EQ(m4d_get_frame(ctx, &held.back()), M4D_OK);
  m4d_close(&ctx);  // frames outlive the context
  ASSERT_EQ(held.size(), 12u);
  for (size_t i = 0; i < held.size(); ++i) {
    EXPECT_EQ(HashOf(held[i]), stream_->recon_hashes[i]) << "frame " << i;
    m4d_frame_unref(&held[i]);
  }
}

TEST(StreamShapes, EverySdkDegreeRoundTrips) {
  for (int sh = 0; sh <= 3; ++sh) {
    TestStreamShape shape;
    shape.gops = 1;
    shape.frames_per_gop = 3;
    shape.static_count = 300;
    shape.dynamic_count = 100;
    shape.sh_degree = sh;
    const TestStream stream = MakeTestStream(shape);
    const DecodeResult r = DecodeWith(DefaultSettings(), stream.packets);
    EXPECT_TRUE(r.errors.empty());
    EXPECT_EQ(r.hashes, stream.recon_hashes) << "sh degree " << sh;
  }
}

TEST(StreamShapes, EmptySetsRoundTrip) {
  TestStreamShape shape;
  shape.gops = 2;
  shape.static_count = 0;
  shape.dynamic_count = 0;
  const TestStream stream = MakeTestStream(shape);
  const DecodeResult r = DecodeWith(DefaultSettings(), stream.packets);
  EXPECT_TRUE(r.errors.empty());
  EXPECT_EQ(r.hashes, stream.recon_hashes);
}

}  // namespace
}  // namespace testing
}  // namespace m4d
