// The differentiable motion of the encoder (paper 3.3, 4.2): agreement with the SDK's
// normative motion, gradients against finite differences, the learned entropy model.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "encoder/src/motion/logistic_entropy_model.h"
#include "encoder/src/motion/motion_field.h"
#include "encoder/src/motion/motion_mlp.h"
#include "encoder/src/motion/motion_stencil.h"
#include "encoder/src/motion/rigid_update.h"
#include "sdk/src/decode/motion_application.h"
#include "sdk/src/layers/gaussian_set.h"
#include "sdk/src/layers/motion_grid.h"

namespace m4d {
namespace {

GridConfig SmallConfig() {
  GridConfig config;
  config.num_levels = 2;
  config.channels[0] = 3;
  config.channels[1] = 2;
  config.resolution[0] = 5;
  config.resolution[1] = 9;
  return config;
}

struct Scene {
  GridBox box;
  std::vector<float> positions, rotations;
  size_t count = 0;
};

// Gaussians in and around the unit box (some outside, which the motion leaves alone).
Scene RandomScene(size_t count, uint32_t seed) {
  Scene s;
  s.count = count;
  s.box.min[0] = -1.0f;
  s.box.min[1] = -0.5f;
  s.box.min[2] = 2.0f;
  s.box.scale[0] = 0.5f;
  s.box.scale[1] = 1.0f;
  s.box.scale[2] = 0.25f;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-0.05f, 1.05f), q(-1.0f, 1.0f);
  for (size_t i = 0; i < count; ++i) {
    for (int a = 0; a < 3; ++a) s.positions.push_back(s.box.min[a] + u(rng) / s.box.scale[a]);
    float r[4], n = 0;
    for (float& v : r) {
      v = q(rng);
      n += v * v;
    }
    for (float v : r) s.rotations.push_back(v / std::sqrt(n));
  }
  return s;
}

void RandomGrid(const GridConfig& config, const MotionStencil& stencil, float amplitude,
                bool integers, uint32_t seed, MotionParameters* params) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-amplitude, amplitude);
  ZeroGrid(config, stencil, params);
  for (int l = 0; l < config.num_levels; ++l) {
    for (float& v : params->grid[l]) v = integers ? std::round(u(rng)) : u(rng);
  }
}

TEST(MotionFieldTest, IntegerGridMovesLikeTheDecoder) {
  const GridConfig config = SmallConfig();
  const float steps[kMaxGridLevels] = {0.01f, 0.02f, 0, 0};
  Scene s = RandomScene(400, 1);
  MotionStencil stencil;
  BuildMotionStencil(config, s.box, s.positions.data(), s.count, &stencil);
  MotionParameters params;
  RandomGrid(config, stencil, 20.0f, true, 2, &params);
  params.mlp = InitialMotionMlp(config.feature_count(), MlpConfig(), 0.5f, 3);

  std::vector<float> moved_p(3 * s.count), moved_q(4 * s.count);
  MotionField field;
  field.Forward(config, steps, stencil, params, s.positions.data(), s.rotations.data(),
                moved_p.data(), moved_q.data());

  // The same grid, dense and quantized, through the SDK.
  MotionGrid grid;
  for (int a = 0; a < 3; ++a) {
    grid.box_min[a] = s.box.min[a];
    grid.box_scale[a] = s.box.scale[a];
  }
  for (int l = 0; l < config.num_levels; ++l) {
    grid.step[l] = steps[l];
    grid.values[l].assign(config.level_values(l), 0);
    for (size_t v = 0; v < stencil.active[l].size(); ++v) {
      for (int c = 0; c < config.channels[l]; ++c) {
        grid.values[l][stencil.active[l][v] * config.channels[l] + c] =
            static_cast<int16_t>(params.grid[l][v * config.channels[l] + c]);
      }
    }
  }
  GaussianSet set;
  set.Resize(s.count);
  std::copy(s.positions.begin(), s.positions.end(), set.positions.begin());
  std::copy(s.rotations.begin(), s.rotations.end(), set.rotations.begin());
  ApplyMotion(config, grid, params.mlp, &set);

  size_t moved = 0, outside = 0;
  for (size_t i = 0; i < s.count; ++i) {
    moved += stencil.inside[i];
    for (int a = 0; a < 3; ++a) {
      if (!stencil.inside[i]) {
        ++outside;
        EXPECT_EQ(moved_p[3 * i + a], s.positions[3 * i + a]);
      }
      // Only the MLP's summation order differs from the normative one.
      EXPECT_NEAR(moved_p[3 * i + a], set.positions[3 * i + a], 1e-5f) << i;
    }
    for (int m = 0; m < 4; ++m) EXPECT_NEAR(moved_q[4 * i + m], set.rotations[4 * i + m], 1e-5f);
  }
  EXPECT_GT(moved, s.count / 2);
  EXPECT_GT(outside, 0u);
}

// L = sum a . p_moved + b . q_moved with fixed random a, b.
double ProbeLoss(const std::vector<float>& p, const std::vector<float>& q,
                 const std::vector<float>& a, const std::vector<float>& b) {
  double l = 0;
  for (size_t i = 0; i < p.size(); ++i) l += double(a[i]) * p[i];
  for (size_t i = 0; i < q.size(); ++i) l += double(b[i]) * q[i];
  return l;
}

TEST(MotionFieldTest, GradientsMatchFiniteDifferences) {
  const GridConfig config = SmallConfig();
  const float steps[kMaxGridLevels] = {0.05f, 0.1f, 0, 0};
  Scene s = RandomScene(60, 4);
  MotionStencil stencil;
  BuildMotionStencil(config, s.box, s.positions.data(), s.count, &stencil);
  MotionParameters params;
  RandomGrid(config, stencil, 3.0f, false, 5, &params);
  params.mlp = InitialMotionMlp(config.feature_count(), MlpConfig{1, 16}, 1.0f, 6);

  std::mt19937 rng(7);
  std::normal_distribution<float> n01;
  std::vector<float> a(3 * s.count), b(4 * s.count);
  for (float& v : a) v = n01(rng);
  for (float& v : b) v = n01(rng);

  MotionField field;
  std::vector<float> p(3 * s.count), q(4 * s.count);
  auto loss = [&]() {
    field.Forward(config, steps, stencil, params, s.positions.data(), s.rotations.data(), p.data(),
                  q.data());
    return ProbeLoss(p, q, a, b);
  };
  loss();
  MotionParameters grad;
  ZeroGrid(config, stencil, &grad);
  grad.mlp = ZeroLike(params.mlp);
  field.Backward(a.data(), b.data(), true, &grad);

  // A frozen MLP: the same grid gradient, and nothing added to the MLP's.
  MotionParameters frozen;
  ZeroGrid(config, stencil, &frozen);
  frozen.mlp = ZeroLike(params.mlp);
  field.Backward(a.data(), b.data(), false, &frozen);
  for (int l = 0; l < config.num_levels; ++l) EXPECT_EQ(frozen.grid[l], grad.grid[l]) << l;
  for (const MlpLayer& layer : frozen.mlp.layers) {
    for (float w : layer.weights) EXPECT_EQ(w, 0.0f);
    for (float w : layer.biases) EXPECT_EQ(w, 0.0f);
  }

  // Central differences in float: eps and bound chosen for float forward passes of O(1).
  const float eps = 2e-3f;
  // Which hidden units are active: finite differences across a LeakyReLU kink are skipped.
  auto active_units = [&]() {
    std::vector<bool> mask;
    const auto& outputs = field.mlp_batch().outputs;
    for (size_t j = 0; j + 1 < outputs.size(); ++j) {
      for (Eigen::Index k = 0; k < outputs[j].size(); ++k) mask.push_back(outputs[j](k) > 0);
    }
    return mask;
  };
  int checked = 0;
  auto check = [&](float* value, float analytic, const std::string& what) {
    const float saved = *value;
    *value = saved + eps;
    double up = loss();
    std::vector<bool> mask_up = active_units();
    *value = saved - eps;
    double down = loss();
    *value = saved;
    if (mask_up != active_units()) return;
    ++checked;
    double numeric = (up - down) / (2 * eps);
    EXPECT_NEAR(analytic, numeric, 2e-3 + 2e-2 * std::fabs(numeric)) << what;
  };
  for (int l = 0; l < config.num_levels; ++l) {
    for (size_t v = 0; v < params.grid[l].size(); v += 7) {
      check(&params.grid[l][v], grad.grid[l][v], "grid " + std::to_string(l));
    }
  }
  for (size_t j = 0; j < params.mlp.layers.size(); ++j) {
    for (size_t w = 0; w < params.mlp.layers[j].weights.size(); w += 5) {
      check(&params.mlp.layers[j].weights[w], grad.mlp.layers[j].weights[w],
            "weight " + std::to_string(j) + " " + std::to_string(w));
    }
    for (size_t w = 0; w < params.mlp.layers[j].biases.size(); ++w) {
      check(&params.mlp.layers[j].biases[w], grad.mlp.layers[j].biases[w],
            "bias " + std::to_string(j) + " " + std::to_string(w));
    }
  }
  EXPECT_GT(checked, 150);  // most probed values are away from kinks
}

TEST(MotionFieldTest, ZeroGridAndInitialMlpDoNotMove) {
  const GridConfig config = SmallConfig();
  const float steps[kMaxGridLevels] = {0.05f, 0.1f, 0, 0};
  Scene s = RandomScene(50, 8);
  MotionStencil stencil;
  BuildMotionStencil(config, s.box, s.positions.data(), s.count, &stencil);
  MotionParameters params;
  ZeroGrid(config, stencil, &params);
  params.mlp = InitialMotionMlp(config.feature_count(), MlpConfig(), 0.1f, 9);
  std::vector<float> p(3 * s.count), q(4 * s.count);
  MotionField field;
  field.Forward(config, steps, stencil, params, s.positions.data(), s.rotations.data(), p.data(),
                q.data());
  for (size_t i = 0; i < p.size(); ++i) EXPECT_EQ(p[i], s.positions[i]);
  for (size_t i = 0; i < q.size(); ++i) EXPECT_NEAR(q[i], s.rotations[i], 1e-6f);
}

TEST(MotionFieldTest, ZeroMotionAtZeroFeaturesKeepsTheSlopes) {
  const int features = 10;
  MlpWeights mlp = InitialMotionMlp(features, MlpConfig{2, 16}, 1.0f, 5);
  std::mt19937 rng(6);
  std::uniform_real_distribution<float> bias(-0.5f, 0.5f);
  for (MlpLayer& layer : mlp.layers) {
    for (float& b : layer.biases) b = bias(rng);
  }
  MlpWeights centred = mlp;
  ZeroMotionAtZeroFeatures(&centred);
  MlpBatch zero, a, b;
  MlpForward(centred, Eigen::MatrixXf::Zero(features, 1), &zero);
  for (int o = 0; o < 7; ++o) EXPECT_NEAR(zero.outputs.back()(o, 0), 0.0f, 1e-6f) << o;
  // Only the last biases moved: outputs shift by the same constant for any features.
  const Eigen::MatrixXf x = Eigen::MatrixXf::Random(features, 4);
  MlpForward(mlp, x, &a);
  MlpForward(centred, x, &b);
  MlpBatch before;
  MlpForward(mlp, Eigen::MatrixXf::Zero(features, 1), &before);
  for (int i = 0; i < 4; ++i) {
    for (int o = 0; o < 7; ++o) {
      EXPECT_NEAR(b.outputs.back()(o, i), a.outputs.back()(o, i) - before.outputs.back()(o, 0),
                  1e-5f);
    }
  }
  EXPECT_GT(before.outputs.back().norm(), 0.1f);  // the random biases did move zero features
}

// The encoder's output must not depend on where the heap puts its vectors (it once changed
// with the length of the output path): the bias gradient of a 32-byte aligned vector and of a
// vector 16 bytes off it are bit-identical.
TEST(MotionFieldTest, MlpGradientsDoNotDependOnTheirAlignment) {
  const int features = 10;
  const MlpWeights mlp = InitialMotionMlp(features, MlpConfig{1, 64}, 1.0f, 7);
  const Eigen::MatrixXf x = Eigen::MatrixXf::Random(features, 75);
  MlpBatch batch;
  MlpForward(mlp, x, &batch);
  const Eigen::MatrixXf d_outputs = Eigen::MatrixXf::Random(7, 75);
  std::vector<std::unique_ptr<MlpWeights>> grads;
  MlpWeights* by_offset[2] = {nullptr, nullptr};  // biases at 0 and 16 bytes mod 32
  for (int attempt = 0; attempt < 256 && !(by_offset[0] && by_offset[1]); ++attempt) {
    grads.push_back(std::make_unique<MlpWeights>(ZeroLike(mlp)));
    const auto address = reinterpret_cast<uintptr_t>(grads.back()->layers[0].biases.data());
    if (address % 16 == 0) by_offset[(address % 32) / 16] = grads.back().get();
  }
  // glibc's malloc alternates; AddressSanitizer's puts these vectors on 32-byte multiples only.
  if (!(by_offset[0] && by_offset[1])) GTEST_SKIP() << "the allocator gives one alignment only";
  for (MlpWeights* grad : by_offset) MlpBackward(mlp, x, batch, d_outputs, grad, nullptr);
  const std::vector<float>& aligned = by_offset[0]->layers[0].biases;
  const std::vector<float>& shifted = by_offset[1]->layers[0].biases;
  ASSERT_EQ(aligned.size(), shifted.size());
  EXPECT_EQ(0, std::memcmp(aligned.data(), shifted.data(), aligned.size() * sizeof(float)));
}

TEST(RigidUpdateTest, BackwardMatchesFiniteDifferences) {
  std::mt19937 rng(10);
  std::normal_distribution<double> n01;
  for (int trial = 0; trial < 20; ++trial) {
    float o[7], p[3], q[4], dp[3], dq[4];
    for (float& v : o) v = 0.3f * static_cast<float>(n01(rng));
    for (float& v : p) v = static_cast<float>(n01(rng));
    for (float& v : q) v = static_cast<float>(n01(rng));
    for (float& v : dp) v = static_cast<float>(n01(rng));
    for (float& v : dq) v = static_cast<float>(n01(rng));
    float d_o[7];
    RigidUpdateBackward(o, q, dp, dq, d_o);
    for (int k = 0; k < 7; ++k) {
      auto loss = [&](float delta) {
        float oo[7], pp[3], qq[4];
        std::copy(o, o + 7, oo);
        oo[k] += delta;
        RigidUpdate(oo, p, q, pp, qq);
        double l = 0;
        for (int a = 0; a < 3; ++a) l += double(dp[a]) * pp[a];
        for (int m = 0; m < 4; ++m) l += double(dq[m]) * qq[m];
        return l;
      };
      const float eps = 1e-3f;
      double numeric = (loss(eps) - loss(-eps)) / (2 * eps);
      EXPECT_NEAR(d_o[k], numeric, 2e-3 + 1e-2 * std::fabs(numeric)) << "output " << k;
    }
  }
}

TEST(LogisticEntropyModelTest, ProbabilitiesSumToOneOverTheIntegers) {
  LogisticEntropyModel model(2, 0.7f);
  std::vector<float> ys;
  for (int y = -2000; y <= 2000; ++y) ys.push_back(static_cast<float>(y));
  double total = 0;
  for (float y : ys) total += std::exp2(-model.Bits(1, &y, 1, 1, 1.0f, nullptr, nullptr));
  EXPECT_NEAR(total, 1.0, 1e-5);  // the probability floor adds 4001 * 1e-9 at most
  // Components 1/100 and 1/25 wide (the first beyond the shared-exp bound) and far tails.
  LogisticEntropyModel narrow(1, 0.01f);
  double narrow_total = 0;
  for (float y : ys) narrow_total += std::exp2(-narrow.Bits(0, &y, 1, 1, 1.0f, nullptr, nullptr));
  EXPECT_NEAR(narrow_total, 1.0, 1e-5);
  EXPECT_GT(std::exp2(-narrow.Bits(0, &ys[2000], 1, 1, 1.0f, nullptr, nullptr)), 0.98);
  // Zero is the likeliest value of the initial model.
  float zero = 0, five = 5;
  EXPECT_LT(model.Bits(0, &zero, 1, 1, 1, nullptr, nullptr),
            model.Bits(0, &five, 1, 1, 1, nullptr, nullptr));
}

TEST(LogisticEntropyModelTest, GradientsMatchFiniteDifferences) {
  LogisticEntropyModel model(2, 0.8f);
  std::mt19937 rng(11);
  std::normal_distribution<float> n01;
  for (float& p : model.parameters()) p += 0.3f * n01(rng);
  std::vector<float> y(40);
  for (float& v : y) v = 3.0f * n01(rng);
  const float scale = 0.7f;
  std::vector<float> d_y(y.size(), 0.0f), d_params(model.parameters().size(), 0.0f);
  model.Bits(1, y.data(), y.size(), 1, scale, d_y.data(), d_params.data());
  auto bits = [&]() { return scale * model.Bits(1, y.data(), y.size(), 1, 1, nullptr, nullptr); };
  const float eps = 1e-3f;
  for (size_t i = 0; i < y.size(); ++i) {
    const float saved = y[i];
    y[i] = saved + eps;
    double up = bits();
    y[i] = saved - eps;
    double down = bits();
    y[i] = saved;
    EXPECT_NEAR(d_y[i], (up - down) / (2 * eps), 1e-2 + 1e-2 * std::fabs(d_y[i]));
  }
  for (size_t k = 0; k < d_params.size(); ++k) {
    float& p = model.parameters()[k];
    const float saved = p;
    p = saved + eps;
    double up = bits();
    p = saved - eps;
    double down = bits();
    p = saved;
    double numeric = (up - down) / (2 * eps);
    if (k < LogisticEntropyModel::kParameters) {
      EXPECT_EQ(d_params[k], 0.0f);  // distribution 0 was not used
    } else {
      EXPECT_NEAR(d_params[k], numeric, 2e-2 + 1e-2 * std::fabs(numeric)) << k;
    }
  }
}

}  // namespace
}  // namespace m4d
