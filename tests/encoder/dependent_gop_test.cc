// Dependent keyframes and STATIC_UPDATE (bitstream 0.3, spec 2, 4.6, 6.2, 6.5, 6.6): a GOP that
// keeps the previous static set decodes to the writer's reconstruction, its static change
// follows the merge of 6.4, decoding cannot start there, a 0.2 stream refuses it, and the
// foreground-only form and a caller background behave as the spec says.
#include <gtest/gtest.h>

#include "tests/encoder/stream_test_util.h"

namespace m4d {
namespace testing {
namespace {

TestStreamShape DependentShape(int static_change_step) {
  TestStreamShape shape;
  shape.dependent_gops = true;
  shape.static_change_step = static_change_step;
  return shape;
}

// Frames per GOP of the default shape, and the packets of its first GOP (SEQUENCE_HEADER,
// KEYFRAME_STATIC, KEYFRAME_DYNAMIC, MLP_WEIGHTS, then two packets per inter frame).
constexpr size_t kFramesPerGop = 4;
constexpr size_t kFirstGopPackets = 4 + 2 * (kFramesPerGop - 1);

M4dSettings StaticOnly() {
  M4dSettings s = DefaultSettings();
  s.layers = M4D_LAYER_STATIC;
  return s;
}

TEST(DependentGop, DecodesToTheWritersReconstruction) {
  for (int step : {0, 50}) {
    const TestStream stream = MakeTestStream(DependentShape(step));
    // One SEQUENCE_HEADER for the whole stream; a STATIC_UPDATE only with a change.
    size_t sequence_headers = 0, updates = 0;
    for (const Packet& p : stream.packets) {
      sequence_headers += p[4] == M4D_PACKET_SEQUENCE_HEADER;
      updates += p[4] == M4D_PACKET_STATIC_UPDATE;
    }
    EXPECT_EQ(sequence_headers, 1u);
    EXPECT_EQ(updates, step > 0 ? 2u : 0u);
    const DecodeResult r = DecodeWith(DefaultSettings(), stream.packets);
    EXPECT_TRUE(r.errors.empty());
    EXPECT_EQ(r.hashes, stream.recon_hashes);
  }
}

TEST(DependentGop, StaticSetStaysOrChangesByItsUpdate) {
  M4dContext* ctx = nullptr;
  const M4dSettings settings = StaticOnly();
  for (int step : {0, 50}) {
    ASSERT_EQ(m4d_open(&ctx, &settings), M4D_OK);
    std::vector<size_t> counts;
    std::vector<std::string> hashes;
    for (const Packet& p : MakeTestStream(DependentShape(step)).packets) {
      ASSERT_EQ(m4d_send_packet(ctx, p.data(), p.size()), M4D_OK);
      M4dFrame frame;
      if (m4d_get_frame(ctx, &frame) != M4D_OK) continue;
      counts.push_back(frame.static_layer.count);
      hashes.push_back(HashOf(frame));
      m4d_frame_unref(&frame);
    }
    m4d_close(&ctx);
    ASSERT_EQ(counts.size(), 12u);
    if (step == 0) {
      for (size_t f = 1; f < 12; ++f) EXPECT_EQ(hashes[f], hashes[0]) << "frame " << f;
      continue;
    }
    // 1500 Gaussians: indices 0, 50, ..., 1450 (30) replaced, 5 appended, at frames 4 and 8.
    EXPECT_EQ(counts[kFramesPerGop - 1], 1500u);
    EXPECT_EQ(counts[kFramesPerGop], 1505u);
    EXPECT_EQ(counts[2 * kFramesPerGop], 1510u);
    EXPECT_NE(hashes[kFramesPerGop], hashes[kFramesPerGop - 1]);
    EXPECT_EQ(hashes[kFramesPerGop + 1], hashes[kFramesPerGop]);
  }
}

// The update changes S in place only when no frame handed out still holds it.
TEST(DependentGop, AHeldFrameKeepsItsStaticLayer) {
  const TestStream stream = MakeTestStream(DependentShape(50));
  M4dContext* ctx = nullptr;
  const M4dSettings settings = StaticOnly();
  ASSERT_EQ(m4d_open(&ctx, &settings), M4D_OK);
  M4dFrame held{};
  std::string held_hash;
  size_t frames = 0;
  for (const Packet& p : stream.packets) {
    ASSERT_EQ(m4d_send_packet(ctx, p.data(), p.size()), M4D_OK);
    M4dFrame frame;
    if (m4d_get_frame(ctx, &frame) != M4D_OK) continue;
    if (++frames == kFramesPerGop) {
      held = frame;  // the last frame before the first dependent keyframe
      held_hash = HashOf(held);
    } else {
      m4d_frame_unref(&frame);
    }
  }
  ASSERT_EQ(frames, 12u);
  EXPECT_EQ(held.static_layer.count, 1500u);
  EXPECT_EQ(HashOf(held), held_hash);
  m4d_frame_unref(&held);
  m4d_close(&ctx);
}

TEST(DependentGop, DecodingCannotStartThere) {
  const TestStream stream = MakeTestStream(DependentShape(50));
  const std::vector<Packet> tail(stream.packets.begin() + kFirstGopPackets, stream.packets.end());
  const DecodeResult r = DecodeWith(DefaultSettings(), tail);
  EXPECT_TRUE(r.errors.empty());  // skipped until a SEQUENCE_HEADER, which never comes
  EXPECT_TRUE(r.hashes.empty());
}

TEST(DependentGop, AVersion02StreamRefusesIt) {
  // 0.3 has 0.2's symbol blocks (one rANS state) and dependent keyframes.
  TestStreamShape shape = DependentShape(50);
  shape.version_minor = 3;
  TestStream stream = MakeTestStream(shape);
  stream.packets[0][24 + 1] = 2;  // version_minor
  FixCrcs(&stream.packets[0]);
  const DecodeResult r = DecodeWith(DefaultSettings(), stream.packets);
  ASSERT_FALSE(r.errors.empty());
  EXPECT_EQ(r.errors[0], M4D_ERR_BITSTREAM);
  ASSERT_EQ(r.hashes.size(), kFramesPerGop);  // the first GOP, a valid 0.2 GOP
  for (size_t f = 0; f < kFramesPerGop; ++f) EXPECT_EQ(r.hashes[f], stream.recon_hashes[f]);
}

TEST(DependentGop, ForegroundOnlyFormDropsTheStaticUpdate) {
  const TestStream stream = MakeTestStream(DependentShape(50));
  std::vector<Packet> foreground;
  for (const Packet& p : stream.packets) {
    if (p[4] != M4D_PACKET_KEYFRAME_STATIC && p[4] != M4D_PACKET_STATIC_UPDATE) {
      foreground.push_back(p);
    }
  }
  M4dSettings dynamic_only = DefaultSettings();
  dynamic_only.layers = M4D_LAYER_DYNAMIC;
  const DecodeResult full = DecodeWith(dynamic_only, stream.packets);
  const DecodeResult stripped = DecodeWith(dynamic_only, foreground);
  EXPECT_TRUE(stripped.errors.empty());
  ASSERT_EQ(stripped.hashes.size(), 12u);
  EXPECT_EQ(stripped.hashes, full.hashes);
}

// A static packet skipped for a caller background leaves S unknown: given back, the stream's
// static layer is empty (not stale, and not an error) until the next SEQUENCE_HEADER.
TEST(DependentGop, StaticLayerGivenBackIsEmptyUntilARandomAccessKeyframe) {
  const TestStream stream = MakeTestStream(DependentShape(50));
  const float center[3] = {5, 5, 5};
  const GaussianSet bg = SyntheticGaussianSet(77, 1, 3, center, 1.0f);
  const M4dGaussians view = GaussianView(bg);
  M4dContext* ctx = nullptr;
  const M4dSettings settings = DefaultSettings();
  ASSERT_EQ(m4d_open(&ctx, &settings), M4D_OK);
  std::vector<size_t> static_counts;
  for (size_t i = 0; i < stream.packets.size(); ++i) {
    if (i == 0) {
      ASSERT_EQ(m4d_set_background(ctx, &view), M4D_OK);
    }
    if (i == kFirstGopPackets - 2) {
      ASSERT_EQ(m4d_set_background(ctx, nullptr), M4D_OK);
    }
    ASSERT_EQ(m4d_send_packet(ctx, stream.packets[i].data(), stream.packets[i].size()), M4D_OK);
    M4dFrame frame;
    if (m4d_get_frame(ctx, &frame) != M4D_OK) continue;
    static_counts.push_back(frame.static_layer.count);
    m4d_frame_unref(&frame);
  }
  m4d_close(&ctx);
  ASSERT_EQ(static_counts.size(), 12u);
  EXPECT_EQ(static_counts[0], 77u);
  for (size_t f = kFramesPerGop - 1; f < 12; ++f) EXPECT_EQ(static_counts[f], 0u) << f;
}

}  // namespace
}  // namespace testing
}  // namespace m4d
