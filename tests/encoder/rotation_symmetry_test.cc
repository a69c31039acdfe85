#include "encoder/src/layers/rotation_symmetry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tests/encoder/gaussian_set_test_util.h"

namespace m4d {
namespace {

using testing::Covariance;
using testing::RelativeDifference;

GaussianSet RandomRotations(size_t n, uint32_t seed) {
  testing::UniformFloats uniform(seed);
  GaussianSet set = testing::ZeroSet(n, 0);
  for (float& v : set.log_scales) v = uniform(-5, 0);
  for (float& v : set.rotations) v = uniform(-1, 1);
  return set;
}

TEST(RotationSymmetryTest, CanonicalRotationsDrawTheSameGaussiansNearTheIdentity) {
  const GaussianSet original = RandomRotations(2000, 3);
  GaussianSet canonical = original;
  std::vector<uint8_t> applied;
  CanonicalizeRotations(&canonical, &applied);
  ASSERT_EQ(applied.size(), original.size());
  float largest = 0.0f;
  size_t changed = 0;
  for (size_t i = 0; i < original.size(); ++i) {
    EXPECT_LT(RelativeDifference(Covariance(original, i), Covariance(canonical, i)), 1e-6) << i;
    const float* q = &canonical.rotations[4 * i];
    EXPECT_GE(q[0], 0.0f);
    for (int c = 1; c < 4; ++c) largest = std::max(largest, std::fabs(q[c]));
    changed += applied[i] != 0;
  }
  EXPECT_LE(largest, kCanonicalRotationBound + 1e-6f);
  EXPECT_GT(largest, 0.9f * kCanonicalRotationBound);  // the bound is reached, not loose
  EXPECT_GT(changed, original.size() * 9 / 10);        // 23 of 24 random rotations move

  // Canonical rotations are their own canonical form.
  GaussianSet again = canonical;
  CanonicalizeRotations(&again, &applied);
  for (size_t i = 0; i < original.size(); ++i) EXPECT_EQ(applied[i], 0) << i;
  EXPECT_EQ(again.log_scales, canonical.log_scales);
}

TEST(RotationSymmetryTest, RestoreGivesBackTheAxesAndTheSign) {
  const GaussianSet original = RandomRotations(500, 4);
  GaussianSet set = original;
  std::vector<uint8_t> applied;
  CanonicalizeRotations(&set, &applied);
  const std::vector<float> rotations(original.rotations.begin(), original.rotations.end());
  RestoreRotationAxes(applied, rotations.data(), &set);
  EXPECT_EQ(set.log_scales, original.log_scales);
  for (size_t i = 0; i < original.size(); ++i) {
    double norm = 0.0;
    for (int c = 0; c < 4; ++c) norm += double{rotations[4 * i + c]} * rotations[4 * i + c];
    for (int c = 0; c < 4; ++c) {
      EXPECT_NEAR(set.rotations[4 * i + c], rotations[4 * i + c] / std::sqrt(norm), 1e-6) << i;
    }
  }
}

TEST(RotationSymmetryTest, ZeroAndNonFiniteQuaternionsStayAsTheyAre) {
  GaussianSet set = RandomRotations(2, 5);
  std::fill(set.rotations.begin(), set.rotations.begin() + 4, 0.0f);
  set.rotations[5] = NAN;
  const GaussianSet before = set;
  std::vector<uint8_t> applied;
  CanonicalizeRotations(&set, &applied);
  EXPECT_EQ(applied, std::vector<uint8_t>({0, 0}));
  EXPECT_EQ(set.log_scales, before.log_scales);
  for (int c = 0; c < 4; ++c) EXPECT_EQ(set.rotations[c], 0.0f);
  EXPECT_TRUE(std::isnan(set.rotations[5]));
}

}  // namespace
}  // namespace m4d
