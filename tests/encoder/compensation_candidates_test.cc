// Initial compensated Gaussians (paper 3.4): replication by gradient, splitting by motion.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "encoder/src/compensation/compensation_candidates.h"

namespace m4d {
namespace {

// The paper's thresholds: tau_g = 1e-4, tau_mu = 0.08, tau_R = pi / 4.
CompensationThresholds PaperThresholds() {
  CompensationThresholds t;
  t.gradient = 1e-4f;
  t.translation = 0.08f;
  t.rotation = 0.78539816f;
  return t;
}

GaussianSet ThreeGaussians() {
  GaussianSet set;
  set.sh_degree = 1;
  set.Resize(3);
  for (size_t i = 0; i < 3; ++i) {
    set.positions[3 * i] = static_cast<float>(i);
    set.rotations[4 * i] = 1.0f;
    set.log_scales[3 * i] = set.log_scales[3 * i + 1] = set.log_scales[3 * i + 2] = -2.0f;
    set.opacity_logits[i] = 0.5f * static_cast<float>(i);
    for (int k = 0; k < set.sh_floats(); ++k) set.sh[12 * i + k] = 0.1f * k + i;
  }
  return set;
}

TEST(CompensationCandidatesTest, ReplicatesWhereTheGradientIsLarge) {
  GaussianSet set = ThreeGaussians();
  std::vector<float> motion(21, 0.0f);
  CompensationCandidates c =
      ProposeCompensation(set, {0.0f, 2e-4f, 5e-5f}, motion, PaperThresholds(), 1);
  EXPECT_EQ(c.replicated, 1u);
  EXPECT_EQ(c.split, 0u);
  ASSERT_EQ(c.added.size(), 1u);
  EXPECT_EQ(c.added.positions[0], 1.0f);
  EXPECT_EQ(c.added.opacity_logits[0], 0.5f);
  EXPECT_EQ(c.added.sh[3], 1.3f);
  EXPECT_EQ(c.removed, (std::vector<uint8_t>{0, 0, 0}));
}

TEST(CompensationCandidatesTest, SplitsLargeTranslationsAndRotations) {
  GaussianSet set = ThreeGaussians();
  std::vector<float> motion(21, 0.0f);
  motion[7 * 0 + 1] = 0.1f;  // translation 0.1 > 0.08
  // A quarter turn about z: increment (cos 45, 0, 0, sin 45) - (1, 0, 0, 0).
  motion[7 * 2 + 3] = std::cos(0.7853982f) - 1.0f;
  motion[7 * 2 + 6] = std::sin(0.7853982f);
  EXPECT_NEAR(IncrementAngle(&motion[14]), 1.5707964f, 1e-5f);
  CompensationCandidates c =
      ProposeCompensation(set, {0.0f, 0.0f, 0.0f}, motion, PaperThresholds(), 2);
  EXPECT_EQ(c.split, 2u);
  ASSERT_EQ(c.added.size(), 4u);
  EXPECT_EQ(c.removed, (std::vector<uint8_t>{1, 0, 1}));
  for (size_t j = 0; j < 4; ++j) {
    const size_t parent = j < 2 ? 0 : 2;
    EXPECT_NEAR(c.added.log_scales[3 * j], -2.0f - std::log(100.0f), 1e-5f);
    // Children stay within a few sqrt(2) sigma of the parent (sigma = e^-2).
    float dx = c.added.positions[3 * j] - static_cast<float>(parent);
    EXPECT_LT(std::fabs(dx), 6 * std::sqrt(2.0f) * std::exp(-2.0f));
  }
  EXPECT_NE(c.added.positions[0], c.added.positions[3]);
  // Deterministic given the seed.
  CompensationCandidates again =
      ProposeCompensation(set, {0.0f, 0.0f, 0.0f}, motion, PaperThresholds(), 2);
  EXPECT_EQ(again.added.positions, c.added.positions);
}

}  // namespace
}  // namespace m4d
