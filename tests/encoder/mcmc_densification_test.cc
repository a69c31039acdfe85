// MCMC densification (mcmc_densification.h): the moment-matched relocation keeps a source's
// rendered footprint, relocation moves only transparent Gaussians, growth stops at the budget
// exactly, and the noise moves only the nearly transparent.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "encoder/src/train/gaussian_optimizer.h"
#include "encoder/src/train/mcmc_densification.h"

namespace m4d {
namespace {

float Logit(float p) { return std::log(p / (1.0f - p)); }
float Sigmoid(float x) { return 1.0f / (1.0f + std::exp(-x)); }

// Integral over a line of the opacity of `copies` coincident 1D Gaussians of scale `scale`,
// each of opacity `opacity`, alpha-composited: 1 - (1 - o g(x))^N.
double CompositeFootprint(double opacity, double scale, int copies) {
  double sum = 0;
  const double dx = scale / 400.0;
  for (double x = -12 * scale; x <= 12 * scale; x += dx) {
    const double g = std::exp(-0.5 * x * x / (scale * scale));
    sum += (1.0 - std::pow(1.0 - opacity * g, copies)) * dx;
  }
  return sum;
}

TEST(McmcDensificationTest, RelocationKeepsTheFootprint) {
  for (float opacity : {0.05f, 0.3f, 0.7f, 0.98f}) {
    for (int copies : {1, 2, 3, 5, 12}) {
      float shared = 0, factor = 0;
      RelocatedOpacityScale(opacity, copies, &shared, &factor);
      // The peak: N copies composite to the source's opacity.
      EXPECT_NEAR(1.0 - std::pow(1.0 - shared, copies), opacity, 1e-5) << opacity << " " << copies;
      // The footprint: integrated over the line, the copies cover what the source covered.
      const double source = CompositeFootprint(opacity, 1.0, 1);
      const double replaced = CompositeFootprint(shared, factor, copies);
      EXPECT_NEAR(replaced / source, 1.0, 2e-3) << opacity << " " << copies;
    }
  }
  float shared = 0, factor = 0;
  RelocatedOpacityScale(0.6f, 1, &shared, &factor);
  EXPECT_FLOAT_EQ(shared, 0.6f);
  EXPECT_NEAR(factor, 1.0f, 1e-6f);
}

GaussianModel Model(const std::vector<float>& opacities) {
  GaussianModel model;
  model.sh_degree = 0;
  model.Resize(opacities.size());
  for (size_t i = 0; i < opacities.size(); ++i) {
    model.opacity_logits[i] = Logit(opacities[i]);
    model.rotations[4 * i] = 1;
    for (int a = 0; a < 3; ++a) {
      model.positions[3 * i + a] = static_cast<float>(i);
      model.log_scales[3 * i + a] = -2.0f;
    }
  }
  return model;
}

McmcSettings RefineAt(int iteration, size_t budget) {
  McmcSettings s;
  s.refine_from = iteration - 1;
  s.refine_until = iteration + 1;
  s.refine_interval = iteration;
  s.max_gaussians = budget;
  return s;
}

TEST(McmcDensificationTest, RelocatesTheTransparentAndGrowsToTheBudget) {
  // Rows 0 and 2 are transparent, row 1 is the only opaque one besides the frozen row 3.
  GaussianModel model = Model({0.001f, 0.8f, 0.004f, 0.9f});
  std::swap(model.opacity_logits[0], model.opacity_logits[3]);  // row 0 frozen and opaque
  AdamOptimizer adam = MakeGaussianOptimizer(model, GaussianLearningRates(), 1.0f);
  TrainingRandom rng(7);
  McmcSettings settings = RefineAt(10, 5);
  settings.frozen = 1;
  McmcDensification mcmc(settings);
  mcmc.Reset(model.size());
  StrategyStep step;
  step.iteration = 10;
  StrategyOutcome outcome;
  ASSERT_TRUE(mcmc.AfterBackward(step, {&model, &adam, &rng}, &outcome).ok());
  EXPECT_TRUE(outcome.rows_changed);
  EXPECT_EQ(outcome.removed, 0u);
  // The frozen row stays; the dead rows 2 and 3 now copy row 1, whose opacity is shared
  // among the three. Growth adds none: 5 % of 4 Gaussians floors to none.
  ASSERT_EQ(model.size(), 4u);
  EXPECT_FLOAT_EQ(Sigmoid(model.opacity_logits[0]), 0.9f);
  float shared = 0, factor = 0;
  RelocatedOpacityScale(0.8f, 3, &shared, &factor);
  for (size_t row : {1u, 2u, 3u}) {
    EXPECT_NEAR(Sigmoid(model.opacity_logits[row]), shared, 1e-5) << row;
    EXPECT_FLOAT_EQ(model.positions[3 * row], 1.0f) << row;
    EXPECT_NEAR(model.log_scales[3 * row], -2.0f + std::log(factor), 1e-5) << row;
  }
  EXPECT_EQ(mcmc.counts().relocated, 2u);

  // Growth: 5 % a refinement, never past the budget.
  GaussianModel big = Model(std::vector<float>(100, 0.5f));
  AdamOptimizer big_adam = MakeGaussianOptimizer(big, GaussianLearningRates(), 1.0f);
  McmcDensification grow(RefineAt(10, 108));
  grow.Reset(big.size());
  ASSERT_TRUE(grow.AfterBackward(step, {&big, &big_adam, &rng}, &outcome).ok());
  EXPECT_EQ(big.size(), 105u);
  EXPECT_EQ(big_adam.rows(), 105u);
  ASSERT_TRUE(grow.AfterBackward(step, {&big, &big_adam, &rng}, &outcome).ok());
  EXPECT_EQ(big.size(), 108u);
  ASSERT_TRUE(grow.AfterBackward(step, {&big, &big_adam, &rng}, &outcome).ok());
  EXPECT_EQ(big.size(), 108u);
  EXPECT_EQ(grow.counts().added, 8u);
  // Outside the refinement window nothing changes.
  step.iteration = 11;
  ASSERT_TRUE(grow.AfterBackward(step, {&big, &big_adam, &rng}, &outcome).ok());
  EXPECT_FALSE(outcome.rows_changed);
}

TEST(McmcDensificationTest, NoiseMovesOnlyTheNearlyTransparent) {
  GaussianModel model = Model({0.001f, 0.5f, 0.999f});
  const GaussianModel before = model;
  AdamOptimizer adam = MakeGaussianOptimizer(model, GaussianLearningRates(), 1.0f);
  TrainingRandom rng(3);
  McmcDensification mcmc(McmcSettings{});
  StrategyStep step;
  step.position_learning_rate = 1e-4f;
  mcmc.AfterStep(step, {&model, &adam, &rng});
  double moved[3] = {0, 0, 0};
  for (size_t i = 0; i < 3; ++i) {
    for (int a = 0; a < 3; ++a) {
      moved[i] += std::fabs(model.positions[3 * i + a] - before.positions[3 * i + a]);
    }
  }
  EXPECT_GT(moved[0], 1e-4);
  EXPECT_LT(moved[1], 1e-6);
  EXPECT_EQ(moved[2], 0.0);
}

TEST(McmcDensificationTest, RegularizationPullsOpacityAndScaleDown) {
  GaussianModel model = Model({0.5f, 0.5f});
  GaussianModel gradients = model;
  gradients.Resize(0);
  gradients.Resize(2);
  McmcDensification mcmc(McmcSettings{});
  mcmc.Regularize(model, &gradients);
  // d/dlogit of 0.01 * mean(sigmoid) is 0.01 / 2 * 0.25; d/dlog-scale of 0.01 * mean(exp)
  // over the 6 scales is 0.01 / 6 * exp(-2).
  EXPECT_NEAR(gradients.opacity_logits[0], 0.01 / 2 * 0.25, 1e-8);
  EXPECT_NEAR(gradients.log_scales[0], 0.01 / 6 * std::exp(-2.0), 1e-8);
}

}  // namespace
}  // namespace m4d
