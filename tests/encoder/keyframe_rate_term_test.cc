// The keyframe rate term (train/keyframe_rate_term.h): its bits are the order-0 entropy of the
// coded levels, and its gradient pulls each value towards the more probable neighbouring level.

#include "encoder/src/train/keyframe_rate_term.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace m4d {
namespace {

// n Gaussians of SH degree 0 whose log scales are all 0 but for the given first ones; the other
// groups are constant (no rate).
GaussianModel ScalesModel(size_t n, const std::vector<float>& first_scales) {
  GaussianModel model;
  model.sh_degree = 0;
  model.Resize(n);
  for (size_t k = 0; k < first_scales.size(); ++k) model.log_scales[k] = first_scales[k];
  return model;
}

GaussianQuantization ThreeBitScales() {
  GaussianQuantization quantization;
  quantization.log_scale_bits = 3;  // levels 0..7 over the range
  return quantization;
}

GaussianModel ZeroGradients(const GaussianModel& model) {
  GaussianModel gradients;
  gradients.sh_degree = model.sh_degree;
  gradients.Resize(model.size());
  return gradients;
}

TEST(KeyframeRateTermTest, BitsAreTheEntropyOfTheLevels) {
  // Range [0, 7]: step 1. Values 7 (level 7) and 3.2 (level 3) once, 3000 zeros.
  const GaussianModel model = ScalesModel(1001, {7.0f, 3.2f});
  GaussianModel gradients = ZeroGradients(model);
  const double bits = AddKeyframeRateGradients(model, ThreeBitScales(), 1.0, 0, &gradients);
  const double total = 3003 + 0.5 * 8;
  const double expected = -3001 * std::log2(3001.5 / total) - 2 * std::log2(1.5 / total);
  EXPECT_NEAR(bits, expected, 1e-6 * expected);
}

TEST(KeyframeRateTermTest, GradientPullsTowardsTheMoreProbableLevel) {
  // Range [0, 7], step 1: level 0 holds 3001 values, level 1 one (1.3), level 7 one. The
  // value at 1.3 lies between level 1 and the empty level 2; the zeros between 0 and 1.
  const GaussianModel model = ScalesModel(1001, {7.0f, 1.3f});
  GaussianModel gradients = ZeroGradients(model);
  AddKeyframeRateGradients(model, ThreeBitScales(), 1.0, 0, &gradients);
  // Descending the gradient lowers a value whose lower level is more probable.
  EXPECT_GT(gradients.log_scales[1], 0.0f);  // 1.3 towards level 1, not 2
  EXPECT_GT(gradients.log_scales[3], 0.0f);  // 0 stays at level 0
  EXPECT_LT(gradients.log_scales[0], 0.0f);  // 7 towards level 7, not the empty level 6
  // lambda scales the gradient.
  GaussianModel doubled = ZeroGradients(model);
  AddKeyframeRateGradients(model, ThreeBitScales(), 2.0, 0, &doubled);
  EXPECT_FLOAT_EQ(doubled.log_scales[1], 2.0f * gradients.log_scales[1]);
}

TEST(KeyframeRateTermTest, RowsBeforeFirstAreCountedButNotMoved) {
  const GaussianModel model = ScalesModel(1001, {7.0f, 1.3f});
  GaussianModel all = ZeroGradients(model), later = ZeroGradients(model);
  const double bits_all = AddKeyframeRateGradients(model, ThreeBitScales(), 1.0, 0, &all);
  const double bits_later = AddKeyframeRateGradients(model, ThreeBitScales(), 1.0, 1, &later);
  EXPECT_EQ(bits_all, bits_later);
  for (int r = 0; r < 3; ++r) EXPECT_EQ(later.log_scales[r], 0.0f);
  for (size_t k = 3; k < all.log_scales.size(); ++k) {
    EXPECT_EQ(later.log_scales[k], all.log_scales[k]);
  }
}

TEST(KeyframeRateTermTest, ZeroWeightOrConstantGroupsAddNothing) {
  const GaussianModel model = ScalesModel(100, {2.0f});
  GaussianModel gradients = ZeroGradients(model);
  EXPECT_EQ(AddKeyframeRateGradients(model, ThreeBitScales(), 0.0, 0, &gradients), 0.0);
  const GaussianModel constant = ScalesModel(100, {});
  EXPECT_EQ(AddKeyframeRateGradients(constant, ThreeBitScales(), 1.0, 0, &gradients), 0.0);
  for (float g : gradients.log_scales) EXPECT_EQ(g, 0.0f);
}

}  // namespace
}  // namespace m4d
