// Adam (train/adam_optimizer.h), the Gaussian optimizer's groups (train/gaussian_optimizer.h)
// and the learning-rate schedule (train/learning_rate_schedule.h).

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "encoder/src/train/adam_optimizer.h"
#include "encoder/src/train/gaussian_model.h"
#include "encoder/src/train/gaussian_optimizer.h"
#include "encoder/src/train/learning_rate_schedule.h"

namespace m4d {
namespace {

// PyTorch's Adam update, in double.
struct ReferenceAdam {
  double m = 0, v = 0;
  int t = 0;
  double Step(double p, double g, double lr) {
    ++t;
    m = 0.9 * m + 0.1 * g;
    v = 0.999 * v + 0.001 * g * g;
    const double bc1 = 1 - std::pow(0.9, t), bc2 = 1 - std::pow(0.999, t);
    return p - lr / bc1 * m / (std::sqrt(v) / std::sqrt(bc2) + 1e-15);
  }
};

TEST(AdamOptimizerTest, FirstStepMovesByTheLearningRate) {
  AdamOptimizer adam;
  adam.ResizeRows(1);
  const int p = adam.AddParameter(1);
  adam.AddGroup("w", p, 0, 1, 0.1f);
  float value = 2.0f;
  const float grad = 0.5f;
  adam.Step(p, &value, &grad, nullptr);
  // m_hat = g, v_hat = g^2: the step is lr * sign(g).
  EXPECT_FLOAT_EQ(value, 1.9f);
  EXPECT_FLOAT_EQ(adam.first_moment(p)[0], 0.05f);
  EXPECT_FLOAT_EQ(adam.second_moment(p)[0], 0.00025f);
  EXPECT_EQ(adam.step_count(0), 1);
}

TEST(AdamOptimizerTest, StepsMatchHandComputation) {
  AdamOptimizer adam;
  adam.ResizeRows(3);
  const int p = adam.AddParameter(2);
  adam.AddGroup("a", p, 0, 1, 0.01f);
  adam.AddGroup("b", p, 1, 1, 0.003f);
  std::vector<float> values = {1, -1, 0.5f, 0.25f, 0, 3};
  std::vector<ReferenceAdam> ref(6);
  std::vector<double> expected(values.begin(), values.end());
  for (int step = 0; step < 20; ++step) {
    std::vector<float> grads(6);
    for (int i = 0; i < 6; ++i) grads[i] = std::sin(1.7f * step + i) * (i + 1) * 0.3f;
    adam.Step(p, values.data(), grads.data(), nullptr);
    for (int i = 0; i < 6; ++i) {
      expected[i] = ref[i].Step(expected[i], grads[i], i % 2 == 0 ? 0.01 : 0.003);
    }
  }
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(values[i], expected[i], 1e-5) << i;
}

TEST(AdamOptimizerTest, FrozenGroupsAndRowEdits) {
  AdamOptimizer adam;
  adam.ResizeRows(3);
  const int p = adam.AddParameter(2);
  const int a = adam.AddGroup("a", p, 0, 1, 0.1f);
  const int b = adam.AddGroup("b", p, 1, 1, 0.1f);
  EXPECT_EQ(adam.FindGroup("b"), b);
  EXPECT_EQ(adam.FindGroup("c"), -1);
  adam.SetFrozen(b, true);
  std::vector<float> values(6, 0.0f);
  const std::vector<float> grads = {1, 1, 2, 2, 3, 3};
  adam.Step(p, values.data(), grads.data(), nullptr);
  EXPECT_EQ(adam.step_count(a), 1);
  EXPECT_EQ(adam.step_count(b), 0);
  EXPECT_FLOAT_EQ(values[0], -0.1f);
  EXPECT_EQ(values[1], 0.0f);  // frozen
  EXPECT_EQ(adam.first_moment(p)[1], 0.0f);

  // Remove row 0, append one: row 1's moments move to row 0, the new row is zero.
  adam.KeepRows({0, 1, 1});
  adam.AppendZeroRows(1);
  EXPECT_EQ(adam.rows(), 3u);
  const std::vector<float>& m = adam.first_moment(p);
  ASSERT_EQ(m.size(), 6u);
  EXPECT_FLOAT_EQ(m[0], 0.2f);
  EXPECT_FLOAT_EQ(m[2], 0.3f);
  EXPECT_EQ(m[4], 0.0f);
  adam.ResetMoments(p);
  EXPECT_EQ(adam.first_moment(p)[0], 0.0f);
  EXPECT_EQ(adam.second_moment(p)[2], 0.0f);
}

TEST(AdamOptimizerTest, ThreadPoolGivesTheSameResult) {
  constexpr size_t kRows = 50000;
  AdamOptimizer one, two;
  for (AdamOptimizer* adam : {&one, &two}) {
    adam->ResizeRows(kRows);
    adam->AddParameter(3);
    adam->AddGroup("x", 0, 0, 3, 0.01f);
  }
  std::vector<float> a(3 * kRows, 1.0f), b = a, grads(3 * kRows);
  for (size_t i = 0; i < grads.size(); ++i) grads[i] = std::cos(0.001f * i);
  ThreadPool pool(2);
  for (int s = 0; s < 3; ++s) {
    one.Step(0, a.data(), grads.data(), nullptr);
    two.Step(0, b.data(), grads.data(), &pool);
  }
  EXPECT_EQ(a, b);
}

TEST(GaussianOptimizerTest, GroupsFollowTheReference) {
  GaussianModel model;
  model.Resize(2);
  GaussianLearningRates rates;
  AdamOptimizer adam = MakeGaussianOptimizer(model, rates, 5.0f);
  ASSERT_EQ(adam.group_count(), 6);
  EXPECT_EQ(adam.group_name(kGroupPositions), "xyz");
  EXPECT_FLOAT_EQ(adam.learning_rate(kGroupPositions), 1.6e-4f * 5.0f);
  EXPECT_FLOAT_EQ(adam.learning_rate(kGroupShDc), 2.5e-3f);
  EXPECT_FLOAT_EQ(adam.learning_rate(kGroupShRest), 2.5e-3f / 20);
  EXPECT_FLOAT_EQ(adam.learning_rate(kGroupOpacity), 0.05f);
  EXPECT_FLOAT_EQ(adam.learning_rate(kGroupScaling), 5e-3f);
  EXPECT_FLOAT_EQ(adam.learning_rate(kGroupRotation), 1e-3f);

  // SH DC and higher bands step at their own rates; frozen groups stay.
  GaussianModel grads;
  grads.Resize(2);
  for (int p = 0; p < kGaussianParameterCount; ++p) {
    for (float& g : grads.values(static_cast<GaussianParameter>(p))) g = 1.0f;
  }
  adam.SetFrozen(kGroupRotation, true);
  StepGaussianOptimizer(grads, kParamOpacityLogits, &adam, &model, nullptr);
  EXPECT_FLOAT_EQ(model.sh[0], -2.5e-3f);
  EXPECT_FLOAT_EQ(model.sh[3], -2.5e-3f / 20);
  EXPECT_FLOAT_EQ(model.sh[48 + 47], -2.5e-3f / 20);
  EXPECT_FLOAT_EQ(model.positions[4], -8e-4f);
  EXPECT_EQ(model.rotations[0], 0.0f);
  EXPECT_EQ(model.opacity_logits[1], 0.0f);  // skipped
  EXPECT_EQ(adam.step_count(kGroupOpacity), 0);
}

TEST(LearningRateScheduleTest, ReferencePositionDecay) {
  const ExponentialDecay decay = GaussianLearningRates().position;
  EXPECT_FLOAT_EQ(decay.At(0), 1.6e-4f);
  EXPECT_FLOAT_EQ(decay.At(15000), 1.6e-5f);  // geometric mean at half way
  EXPECT_FLOAT_EQ(decay.At(7500), 1.6e-4f * std::pow(0.01f, 0.25f));
  EXPECT_FLOAT_EQ(decay.At(30000), 1.6e-6f);
  EXPECT_FLOAT_EQ(decay.At(40000), 1.6e-6f);
  EXPECT_EQ(decay.At(-1), 0.0f);
  const ExponentialDecay off{0, 0, 100};
  EXPECT_EQ(off.At(5), 0.0f);
}

TEST(LearningRateScheduleTest, DelayWarmsUp) {
  ExponentialDecay decay{1e-3f, 1e-5f, 1000, 100, 0.01f};
  EXPECT_FLOAT_EQ(decay.At(0), 1e-5f);  // 0.01 x initial
  const float at50 = 1e-3f * std::pow(0.01f, 0.05f) *
                     (0.01f + 0.99f * static_cast<float>(std::sin(3.14159265 / 4)));
  EXPECT_NEAR(decay.At(50), at50, 1e-9);
  EXPECT_FLOAT_EQ(decay.At(100), 1e-3f * std::pow(0.01f, 0.1f));
}

}  // namespace
}  // namespace m4d
