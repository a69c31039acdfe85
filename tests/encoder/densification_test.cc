// Adaptive density control (train/densification.h): statistics, clone / split / prune
// counts, optimizer moments following the rows, the cap and the opacity reset.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "encoder/src/raster/viewspace_gradient.h"
#include "encoder/src/train/adam_optimizer.h"
#include "encoder/src/train/densification.h"
#include "encoder/src/train/gaussian_model.h"
#include "encoder/src/train/gaussian_optimizer.h"
#include "sdk/src/render/projected_splats.h"

namespace m4d {
namespace {

float Logit(float p) { return std::log(p / (1 - p)); }

// Gaussians at x = i, isotropic scale `scales[i]`, opacity `opacities[i]`, distinct SH.
GaussianModel Model(const std::vector<float>& scales, const std::vector<float>& opacities) {
  GaussianModel model;
  model.Resize(scales.size());
  for (size_t i = 0; i < scales.size(); ++i) {
    model.positions[3 * i] = static_cast<float>(i);
    for (int a = 0; a < 3; ++a) model.log_scales[3 * i + a] = std::log(scales[i]);
    model.rotations[4 * i] = 1.0f;
    model.opacity_logits[i] = Logit(opacities[i]);
    for (int j = 0; j < 48; ++j) model.sh[48 * i + j] = static_cast<float>(100 * i + j);
  }
  return model;
}

// One view in which every Gaussian is visible with radius radii[i] and a view-space
// gradient of norm grads[i] (NDC units) along x.
void AddView(const std::vector<float>& grads, const std::vector<float>& radii,
             DensificationStats* stats) {
  constexpr int kWidth = 64, kHeight = 48;
  ProjectedSplats splats;
  splats.Resize(grads.size());
  std::vector<float> mean2d(2 * grads.size(), 0.0f);
  for (size_t i = 0; i < grads.size(); ++i) {
    splats.radius[i] = radii[i];
    mean2d[2 * i] = grads[i] / (0.5f * kWidth);  // pixels
  }
  stats->Accumulate(splats, mean2d.data(), kWidth, kHeight);
}

// An optimizer whose moments of row i are i + 1 (one step with gradients i + 1).
AdamOptimizer OptimizerWithMoments(GaussianModel* model) {
  AdamOptimizer adam = MakeGaussianOptimizer(*model, GaussianLearningRates(), 1.0f);
  GaussianModel grads = *model;
  for (int p = 0; p < kGaussianParameterCount; ++p) {
    const auto param = static_cast<GaussianParameter>(p);
    const int w = grads.width(param);
    for (size_t i = 0; i < grads.size(); ++i) {
      for (int c = 0; c < w; ++c) grads.values(param)[i * w + c] = static_cast<float>(i + 1);
    }
  }
  GaussianModel copy = *model;
  StepGaussianOptimizer(grads, kGaussianParameterCount, &adam, &copy, nullptr);
  return adam;
}

TEST(DensificationTest, StatisticsAverageOverVisibleViews) {
  DensificationStats stats;
  stats.Reset(3);
  AddView({0.001f, 0.002f, 0.5f}, {3, 0, 7}, &stats);
  AddView({0.003f, 0.002f, 0.5f}, {5, 2, 0}, &stats);
  EXPECT_EQ(stats.views(0), 2u);
  EXPECT_EQ(stats.views(1), 1u);
  EXPECT_NEAR(stats.MeanGradient(0), 0.002f, 1e-8f);
  EXPECT_NEAR(stats.MeanGradient(1), 0.002f, 1e-8f);
  EXPECT_NEAR(stats.MeanGradient(2), 0.5f, 1e-6f);
  EXPECT_EQ(stats.max_radius(0), 5.0f);
  EXPECT_EQ(stats.max_radius(2), 7.0f);
}

TEST(DensificationTest, ClonesSplitsPrunesAndMovesMoments) {
  // Extent 1: clone at scale <= 0.01, split above. 0: small, large gradient (clone);
  // 1: large, large gradient (split); 2: transparent (prune); 3: small gradient (stays).
  GaussianModel model = Model({0.005f, 0.05f, 0.02f, 0.02f}, {0.5f, 0.5f, 0.004f, 0.5f});
  AdamOptimizer adam = OptimizerWithMoments(&model);
  const std::vector<float> m_before = adam.first_moment(kParamSh);
  DensificationStats stats;
  stats.Reset(4);
  AddView({0.001f, 0.0003f, 0.0f, 0.0001f}, {4, 4, 4, 4}, &stats);
  TrainingRandom rng(1);
  DensifyCounts counts;
  ASSERT_TRUE(
      DensifyAndPrune(DensificationSettings(), 1.0f, false, &rng, &model, &adam, &stats, &counts)
          .ok());
  EXPECT_EQ(counts.cloned, 1u);
  EXPECT_EQ(counts.split, 1u);
  EXPECT_EQ(counts.pruned, 1u);
  // Rows: 0, 3, the clone of 0, two children of 1.
  ASSERT_EQ(model.size(), 5u);
  EXPECT_EQ(adam.rows(), 5u);
  EXPECT_EQ(stats.size(), 5u);
  EXPECT_EQ(stats.views(0), 0u);  // restarted
  EXPECT_EQ(model.positions[3 * 1], 3.0f);
  EXPECT_EQ(model.positions[3 * 2], 0.0f);
  EXPECT_EQ(model.sh[48 * 2 + 5], 5.0f);  // the clone copies everything
  EXPECT_EQ(model.log_scales[3 * 2], std::log(0.005f));
  for (size_t child : {3u, 4u}) {
    EXPECT_EQ(model.sh[48 * child + 7], 107.0f);
    EXPECT_FLOAT_EQ(model.log_scales[3 * child + 1], std::log(0.05f) - std::log(1.6f));
    const float dx = model.positions[3 * child] - 1.0f;
    const float dy = model.positions[3 * child + 1];
    EXPECT_GT(std::abs(dx) + std::abs(dy), 0.0f);  // sampled, not copied
    EXPECT_LT(std::sqrt(dx * dx + dy * dy), 6 * 0.05f);
  }
  EXPECT_NE(model.positions[9], model.positions[12]);
  // Moments: rows 0 and 1 keep those of Gaussians 0 and 3, new rows start at zero.
  const std::vector<float>& m = adam.first_moment(kParamSh);
  EXPECT_EQ(m[0], m_before[0]);
  EXPECT_EQ(m[48 + 10], m_before[3 * 48 + 10]);
  EXPECT_NE(m[48 + 10], 0.0f);
  for (size_t j = 2 * 48; j < 5 * 48; ++j) EXPECT_EQ(m[j], 0.0f);
  EXPECT_EQ(adam.step_count(kGroupShDc), 1);  // steps survive the edits
}

TEST(DensificationTest, PrunesBySizeOnlyWhenAsked) {
  // 0: large on screen; 1: large in the world (0.2 > 0.1 x extent 1); 2: fine.
  for (bool by_size : {false, true}) {
    GaussianModel model = Model({0.005f, 0.2f, 0.005f}, {0.5f, 0.5f, 0.5f});
    AdamOptimizer adam = MakeGaussianOptimizer(model, GaussianLearningRates(), 1.0f);
    DensificationStats stats;
    stats.Reset(3);
    AddView({0, 0, 0}, {25, 3, 19}, &stats);
    TrainingRandom rng(1);
    DensifyCounts counts;
    ASSERT_TRUE(DensifyAndPrune(DensificationSettings(), 1.0f, by_size, &rng, &model, &adam, &stats,
                                &counts)
                    .ok());
    EXPECT_EQ(counts.pruned, by_size ? 2u : 0u);
    EXPECT_EQ(model.size(), by_size ? 1u : 3u);
    if (by_size) {
      EXPECT_EQ(model.positions[0], 2.0f);
    }
  }
}

TEST(DensificationTest, CapKeepsTheLargestGradients) {
  GaussianModel model = Model({0.005f, 0.005f, 0.05f, 0.005f}, {0.5f, 0.5f, 0.5f, 0.5f});
  AdamOptimizer adam = MakeGaussianOptimizer(model, GaussianLearningRates(), 1.0f);
  DensificationStats stats;
  stats.Reset(4);
  AddView({0.001f, 0.003f, 0.002f, 0.0f}, {2, 2, 2, 2}, &stats);
  DensificationSettings settings;
  settings.max_gaussians = 6;  // room for two of the three candidates
  TrainingRandom rng(1);
  DensifyCounts counts;
  ASSERT_TRUE(DensifyAndPrune(settings, 1.0f, false, &rng, &model, &adam, &stats, &counts).ok());
  EXPECT_EQ(counts.cloned, 1u);  // Gaussian 1 (0.003); Gaussian 0 (0.001) loses
  EXPECT_EQ(counts.split, 1u);   // Gaussian 2 (0.002)
  EXPECT_EQ(model.size(), 6u);
  EXPECT_EQ(model.positions[3 * 3], 1.0f);  // rows 0, 1, 3, the clone of 1, two children
  // A full model does not grow.
  settings.max_gaussians = 6;
  stats.Reset(6);
  AddView({1, 1, 1, 1, 1, 1}, {2, 2, 2, 2, 2, 2}, &stats);
  ASSERT_TRUE(DensifyAndPrune(settings, 1.0f, false, &rng, &model, &adam, &stats, &counts).ok());
  EXPECT_EQ(counts.cloned + counts.split, 0u);
  EXPECT_EQ(model.size(), 6u);
}

TEST(DensificationTest, PruningIsBoundedMostTransparentFirst) {
  GaussianModel model = Model({0.005f, 0.005f, 0.005f, 0.005f, 0.005f, 0.005f},
                              {0.001f, 0.004f, 0.002f, 0.5f, 0.003f, 0.0005f});
  AdamOptimizer adam = MakeGaussianOptimizer(model, GaussianLearningRates(), 1.0f);
  DensificationStats stats;
  stats.Reset(6);
  DensificationSettings settings;
  settings.max_prune_fraction = 0.5f;  // 3 of the 5 below min_opacity
  TrainingRandom rng(1);
  DensifyCounts counts;
  ASSERT_TRUE(DensifyAndPrune(settings, 1.0f, false, &rng, &model, &adam, &stats, &counts).ok());
  EXPECT_EQ(counts.pruned, 3u);
  ASSERT_EQ(model.size(), 3u);
  EXPECT_EQ(model.positions[0], 1.0f);  // rows 1, 3 and 4 stay
  EXPECT_EQ(model.positions[3], 3.0f);
  EXPECT_EQ(model.positions[6], 4.0f);
  EXPECT_EQ(adam.rows(), 3u);
  settings.max_prune_fraction = 1.0f;
  ASSERT_TRUE(DensifyAndPrune(settings, 1.0f, false, &rng, &model, &adam, &stats, &counts).ok());
  EXPECT_EQ(counts.pruned, 2u);
}

TEST(DensificationTest, OpacityResetLowersOpacitiesAndMoments) {
  GaussianModel model = Model({0.01f, 0.01f}, {0.9f, 0.005f});
  AdamOptimizer adam = OptimizerWithMoments(&model);
  const std::vector<float> scale_moments = adam.first_moment(kParamLogScales);
  ResetOpacity(0.01f, &model, &adam);
  EXPECT_NEAR(1.0f / (1.0f + std::exp(-model.opacity_logits[0])), 0.01f, 1e-6f);
  EXPECT_FLOAT_EQ(model.opacity_logits[1], Logit(0.005f));
  EXPECT_EQ(adam.first_moment(kParamOpacityLogits)[0], 0.0f);
  EXPECT_EQ(adam.second_moment(kParamOpacityLogits)[1], 0.0f);
  EXPECT_EQ(adam.first_moment(kParamLogScales), scale_moments);
}

TEST(DensificationTest, MismatchedStateIsRejected) {
  GaussianModel model = Model({0.01f, 0.01f}, {0.5f, 0.5f});
  AdamOptimizer adam = MakeGaussianOptimizer(model, GaussianLearningRates(), 1.0f);
  DensificationStats stats;
  stats.Reset(3);
  TrainingRandom rng(1);
  EXPECT_EQ(
      DensifyAndPrune(DensificationSettings(), 1.0f, false, &rng, &model, &adam, &stats, nullptr)
          .code(),
      M4D_ERR_INVALID_ARG);
  stats.Reset(2);
  EXPECT_EQ(
      DensifyAndPrune(DensificationSettings(), 0.0f, false, &rng, &model, &adam, &stats, nullptr)
          .code(),
      M4D_ERR_INVALID_ARG);
}

}  // namespace
}  // namespace m4d
