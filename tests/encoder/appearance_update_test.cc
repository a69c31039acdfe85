// APPEARANCE (bitstream 0.3, spec 4.7, 6.7): the colour change of the moved dynamic set adds
// float(q) * step to each SH DC coefficient and nothing else, persists through the GOP as the
// writer reconstructs it, is refused in a 0.2 stream, and is skipped with the dynamic layer.
#include <gtest/gtest.h>

#include <cstring>

#include "tests/encoder/stream_test_util.h"

namespace m4d {
namespace testing {
namespace {

TestStreamShape AppearanceShape() {
  TestStreamShape shape;
  shape.appearance = true;
  return shape;
}

StreamWriterOptions SmallOptions(int version_minor) {
  StreamWriterOptions options;
  options.sequence.sh_degree = 1;
  options.sequence.version_minor = version_minor;
  options.sequence.grid.resolution[0] = 8;
  options.sequence.grid.resolution[1] = 12;
  options.sequence.grid.resolution[2] = 20;
  options.sequence.mlp.hidden_width = 16;
  return options;
}

// A writer after one keyframe and frame 1's motion.
Status StartInterFrame(StreamWriter* writer, const StreamWriterOptions& options) {
  const float center[3] = {0, 0, 0}, fg[3] = {0.1f, 0.2f, -0.1f};
  DecodedFrame recon;
  M4D_RETURN_IF_ERROR(writer->WriteKeyframe(
      SyntheticGaussianSet(300, 1, 7, center, 2.0f), SyntheticGaussianSet(90, 1, 8, fg, 0.4f),
      SyntheticMlp(options.sequence.grid.feature_count(), options.sequence.mlp, 9), &recon));
  return writer->WriteMotion(SyntheticMotionGrid(options.sequence.grid, 10, -0.6f, 0.6f, 0.2f));
}

bool SameBits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

TEST(AppearanceUpdate, AddsTheDequantizedValueToTheDcOnly) {
  const StreamWriterOptions options = SmallOptions(3);
  StreamWriter writer(options);
  ASSERT_TRUE(StartInterFrame(&writer, options).ok());
  const GaussianSet before = writer.moved_dynamic_set();
  const std::vector<int32_t> values = TestAppearanceValues(before.size(), 1);
  ASSERT_TRUE(writer.WriteAppearance(kTestAppearanceStep, values).ok());
  const GaussianSet& after = writer.moved_dynamic_set();
  ASSERT_EQ(after.size(), before.size());
  EXPECT_EQ(after.positions, before.positions);
  EXPECT_EQ(after.rotations, before.rotations);
  EXPECT_EQ(after.log_scales, before.log_scales);
  EXPECT_EQ(after.opacity_logits, before.opacity_logits);
  const size_t stride = static_cast<size_t>(before.sh_floats());
  size_t changed = 0;
  for (size_t i = 0; i < before.size(); ++i) {
    for (size_t k = 0; k < stride; ++k) {
      const float old_value = before.sh[i * stride + k];
      float expected = old_value;
      if (k < 3) {
        const float change = static_cast<float>(values[3 * i + k]) * kTestAppearanceStep;
        expected = old_value + change;
        changed += values[3 * i + k] != 0;
      }
      ASSERT_TRUE(SameBits(after.sh[i * stride + k], expected)) << "Gaussian " << i << " k " << k;
    }
  }
  EXPECT_GT(changed, before.size() / 2);
}

TEST(AppearanceUpdate, DecodesToTheWritersReconstruction) {
  const TestStream stream = MakeTestStream(AppearanceShape());
  size_t appearance_packets = 0;
  for (const Packet& p : stream.packets) appearance_packets += p[4] == M4D_PACKET_APPEARANCE;
  EXPECT_EQ(appearance_packets, 3u * 3u);  // every inter frame of 3 GOPs of 4 frames
  const DecodeResult r = DecodeWith(DefaultSettings(), stream.packets);
  EXPECT_TRUE(r.errors.empty());
  EXPECT_EQ(r.hashes, stream.recon_hashes);
  // The colours differ from the same stream without the change from frame 1 on.
  const TestStream plain = MakeTestStream();
  ASSERT_EQ(plain.recon_hashes.size(), stream.recon_hashes.size());
  EXPECT_EQ(plain.recon_hashes[0], stream.recon_hashes[0]);
  EXPECT_NE(plain.recon_hashes[1], stream.recon_hashes[1]);
}

TEST(AppearanceUpdate, RefusedInAVersion02Stream) {
  const StreamWriterOptions options = SmallOptions(2);
  StreamWriter writer(options);
  ASSERT_TRUE(StartInterFrame(&writer, options).ok());
  const Status status = writer.WriteAppearance(
      kTestAppearanceStep, TestAppearanceValues(writer.moved_dynamic_set().size(), 1));
  EXPECT_EQ(status.code(), M4D_ERR_BITSTREAM);
}

TEST(AppearanceUpdate, SkippedWithoutTheDynamicLayer) {
  const TestStream stream = MakeTestStream(AppearanceShape());
  M4dSettings settings = DefaultSettings();
  settings.layers = M4D_LAYER_STATIC;
  const DecodeResult with = DecodeWith(settings, stream.packets);
  const DecodeResult without = DecodeWith(settings, MakeTestStream().packets);
  EXPECT_TRUE(with.errors.empty());
  EXPECT_EQ(with.hashes, without.hashes);  // the static layer alone does not see it
  EXPECT_EQ(with.hashes.size(), stream.recon_hashes.size());
}

}  // namespace
}  // namespace testing
}  // namespace m4d
