#include "encoder/src/pipeline/gop_policy.h"

#include <gtest/gtest.h>

namespace m4d {
namespace {

TEST(GopPolicyTest, ImposedStartsReplaceTheLengths) {
  EncoderOptions o;
  o.gop.max_length = 2;
  o.gop.starts = {5, 9};
  const GopPolicy policy(o);
  EXPECT_FALSE(policy.EndsBefore(0, 4));
  EXPECT_TRUE(policy.EndsBefore(0, 5));
  EXPECT_TRUE(policy.EndsBefore(5, 9));
  // Nor does the adaptive rule restart such a GOP.
  EXPECT_FALSE(policy.Restarts(3, 1.0, 10.0, 40.0));
}

TEST(GopPolicyTest, FixedAndMaximumLengths) {
  EncoderOptions o;
  o.gop.max_length = 10;
  EXPECT_FALSE(GopPolicy(o).EndsBefore(0, 9));
  EXPECT_TRUE(GopPolicy(o).EndsBefore(0, 10));
  o.gop.fixed_length = 3;  // only when not adaptive
  EXPECT_FALSE(GopPolicy(o).EndsBefore(4, 7));
  o.gop.adaptive = false;
  EXPECT_FALSE(GopPolicy(o).EndsBefore(4, 6));
  EXPECT_TRUE(GopPolicy(o).EndsBefore(4, 7));
}

TEST(GopPolicyTest, AdaptiveRuleOnRatioAndQualityDrop) {
  EncoderOptions o;
  o.gop.threshold = 0.15f;
  o.gop.max_psnr_drop = 2.5f;
  o.gop.min_length = 2;
  const GopPolicy policy(o);
  EXPECT_FALSE(policy.Restarts(2, 0.1, 30.0, 31.0));
  EXPECT_TRUE(policy.Restarts(2, 0.2, 30.0, 31.0));
  EXPECT_TRUE(policy.Restarts(2, 0.1, 28.0, 31.0));
  EXPECT_FALSE(policy.Restarts(1, 0.2, 28.0, 31.0));  // shorter than min_length
  o.gop.max_psnr_drop = 0;                            // the quality guard off
  EXPECT_FALSE(GopPolicy(o).Restarts(2, 0.1, 20.0, 31.0));
  o.gop.adaptive = false;
  EXPECT_FALSE(GopPolicy(o).Restarts(2, 0.9, 20.0, 31.0));
}

TEST(GopPolicyTest, DependentWithinTheRandomAccessInterval) {
  EncoderOptions o;
  o.fps_num = 30;
  o.fps_den = 1;
  o.gop.random_access_seconds = 0.1;  // 3 frames
  GopPolicy policy(o);
  policy.Started(0, false);
  EXPECT_TRUE(policy.Dependent(2));
  policy.Started(2, true);  // a dependent GOP does not restart the interval
  EXPECT_FALSE(policy.Dependent(3));
  policy.Started(3, false);
  EXPECT_TRUE(policy.Dependent(5));
  EXPECT_FALSE(policy.Dependent(6));
  o.gop.random_access_seconds = 0;
  EXPECT_FALSE(GopPolicy(o).Dependent(1));
  o.gop.random_access_seconds = 10;
  o.independent_frames = true;
  EXPECT_FALSE(GopPolicy(o).Dependent(1));
}

TEST(GopPolicyTest, MayRestartWhereAnyRuleCanEndAGop) {
  EncoderOptions o;
  o.gop.min_length = 2;
  EXPECT_FALSE(GopPolicy(o).MayRestart(0, 2));  // the adaptive rule needs a third frame
  EXPECT_TRUE(GopPolicy(o).MayRestart(0, 3));
  o.gop.adaptive = false;
  o.gop.max_length = 300;
  EXPECT_FALSE(GopPolicy(o).MayRestart(0, 300));
  EXPECT_TRUE(GopPolicy(o).MayRestart(0, 301));
  o.gop.fixed_length = 4;
  EXPECT_FALSE(GopPolicy(o).MayRestart(0, 4));
  EXPECT_TRUE(GopPolicy(o).MayRestart(0, 5));
  o.gop.adaptive = true;  // imposed starts replace every rule
  o.gop.starts = {10, 20};
  EXPECT_FALSE(GopPolicy(o).MayRestart(10, 10));
  EXPECT_TRUE(GopPolicy(o).MayRestart(10, 11));
  EXPECT_FALSE(GopPolicy(o).MayRestart(20, 50));
  o.gop.starts.clear();
  o.independent_frames = true;
  EXPECT_TRUE(GopPolicy(o).MayRestart(0, 2));
  EXPECT_FALSE(GopPolicy(o).MayRestart(0, 1));
}

}  // namespace
}  // namespace m4d
