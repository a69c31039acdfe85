// Rate points: the ladder runs from fewest bytes to most in every setting it steers, any
// lambda_2 finds its nearest point, and the compensated Gaussians' own bit depths reach the
// stream (fewer bytes, decoded by the SDK to the writer's reconstruction).
#include <gtest/gtest.h>

#include "encoder/src/pipeline/rate_points.h"
#include "tests/encoder/stream_test_util.h"

namespace m4d {
namespace testing {
namespace {

int TotalBits(const GaussianQuantization& q) {
  return q.position_bits + q.log_scale_bits + q.rotation_bits + q.opacity_bits + q.sh_dc_bits +
         q.sh_rest_bits;
}

TEST(RatePoints, LadderSpendsMoreAtEveryStep) {
  const std::vector<RatePointSettings>& points = RatePoints();
  ASSERT_EQ(points.size(), 5u);
  for (size_t i = 1; i < points.size(); ++i) {
    const RatePointSettings &a = points[i - 1], &b = points[i];
    EXPECT_EQ(b.name, "r" + std::to_string(i + 1));
    EXPECT_LT(b.motion_rate_weight, a.motion_rate_weight);
    EXPECT_LT(b.replication_gradient, a.replication_gradient);
    EXPECT_GT(TotalBits(b.keyframe), TotalBits(a.keyframe));
    EXPECT_GE(TotalBits(b.compensation), TotalBits(a.compensation));
  }
  // The paper's set.
  EXPECT_DOUBLE_EQ(points.front().motion_rate_weight, 5e-4);
  EXPECT_DOUBLE_EQ(points.back().motion_rate_weight, 5e-5);
}

TEST(RatePoints, FindByName) {
  RatePointSettings p;
  ASSERT_TRUE(FindRatePoint("r3", &p).ok());
  EXPECT_EQ(p.motion_rate_weight, 2e-4);
  const Status s = FindRatePoint("r6", &p);
  EXPECT_EQ(s.code(), M4D_ERR_INVALID_ARG);
  EXPECT_NE(s.message().find("r6"), std::string::npos);
}

TEST(RatePoints, LambdaTakesTheNearestPointsSettings) {
  // 1.5e-4 is nearer 2e-4 (r3) than 1e-4 (r4) on a log scale: ln(4/3) < ln(3/2).
  const RatePointSettings p = RatePointForLambda(1.5e-4);
  EXPECT_EQ(p.name, "r3");
  EXPECT_EQ(p.motion_rate_weight, 1.5e-4);
  EXPECT_EQ(RatePointForLambda(1.4e-4).name, "r4");
  EXPECT_EQ(RatePointForLambda(1.0).name, "r1");
  EXPECT_EQ(RatePointForLambda(0.0).name, "r5");  // no rate term: the finest point
  EXPECT_EQ(RatePointForLambda(0.0).motion_rate_weight, 0.0);
}

TEST(RatePoints, ApplySetsWhatThePointSteers) {
  EncoderOptions options;
  RatePointSettings p;
  ASSERT_TRUE(FindRatePoint("r1", &p).ok());
  ApplyRatePoint(p, &options);
  EXPECT_EQ(options.motion.rate_weight, 5e-4);
  EXPECT_EQ(options.compensation_thresholds.gradient, p.replication_gradient);
  EXPECT_EQ(QuantizationName(options.quantization), "10/5/4/5/5/3 codebooks 0/1024/2");
  EXPECT_EQ(QuantizationName(options.compensation_quantization), QuantizationName(p.compensation));
}

// One keyframe and one inter frame; returns the compensation packet's bytes and checks that
// the SDK decodes the writer's reconstruction of both frames.
size_t CompensationBytes(const GaussianQuantization& compensation) {
  StreamWriterOptions options;
  options.sequence.grid.resolution[0] = 8;
  options.sequence.grid.resolution[1] = 12;
  options.sequence.grid.resolution[2] = 20;
  options.sequence.mlp.hidden_width = 16;
  options.sequence.sh_degree = 1;
  options.compensation_quantization = compensation;
  StreamWriter writer(options);
  const float center[3] = {0, 0, 0};
  std::vector<std::string> hashes;
  DecodedFrame recon;
  EXPECT_TRUE(writer
                  .WriteKeyframe(
                      SyntheticGaussianSet(300, 1, 1, center, 2.0f),
                      SyntheticGaussianSet(200, 1, 2, center, 0.4f),
                      SyntheticMlp(options.sequence.grid.feature_count(), options.sequence.mlp, 3),
                      &recon)
                  .ok());
  hashes.push_back(FrameHashHex(recon));
  EXPECT_TRUE(
      writer.WriteMotion(SyntheticMotionGrid(options.sequence.grid, 4, -0.5f, 0.5f, 0.2f)).ok());
  const size_t keyframe_bytes = writer.bytes().size();
  std::vector<uint8_t> removed(writer.moved_dynamic_set().size(), 0);
  EXPECT_TRUE(
      writer.WriteCompensation(removed, SyntheticGaussianSet(500, 1, 5, center, 0.4f), &recon)
          .ok());
  hashes.push_back(FrameHashHex(recon));
  const DecodeResult r = DecodeWith(DefaultSettings(), SplitPackets(writer.bytes()));
  EXPECT_TRUE(r.errors.empty());
  EXPECT_EQ(r.hashes, hashes);
  return writer.bytes().size() - keyframe_bytes;
}

TEST(RatePoints, CompensationBitsReachTheStream) {
  RatePointSettings r1, r5;
  ASSERT_TRUE(FindRatePoint("r1", &r1).ok());
  ASSERT_TRUE(FindRatePoint("r5", &r5).ok());
  const size_t coarse = CompensationBytes(r1.compensation);
  const size_t fine = CompensationBytes(r5.compensation);
  const size_t keyframe_bits = CompensationBytes(GaussianQuantization());
  // 500 Gaussians: r5 spends 3 bits more per Gaussian on position alone.
  EXPECT_LT(coarse + 500 * 3 / 8, fine);
  EXPECT_LT(fine, keyframe_bits);
}

}  // namespace
}  // namespace testing
}  // namespace m4d
