// Motion estimation of one frame (paper 3.3, 4.2): a dynamic blob that translates between
// two frames over a random static background; the grid and MLP learn the translation.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "encoder/src/motion/motion_estimation.h"
#include "encoder/src/motion/motion_mlp.h"
#include "encoder/src/raster/splat_renderer.h"
#include "encoder/src/train/training_views.h"
#include "tests/raster/splat_test_scenes.h"

namespace m4d {
namespace {

constexpr int kWidth = 64, kHeight = 48, kCameras = 6;
const float kShift[3] = {0.12f, -0.06f, 0.0f};

struct Scene {
  GaussianSet static_set, dynamic_set, moved_truth;
  TrainingViews views;  // frame t
};

GaussianSet Shifted(const GaussianSet& set) {
  GaussianSet moved = set;
  for (size_t i = 0; i < set.size(); ++i) {
    for (int a = 0; a < 3; ++a) moved.positions[3 * i + a] += kShift[a];
  }
  return moved;
}

// red_change: added to the moved blob's red SH DC coefficient in frame t (its shading changed).
Scene MakeScene(float red_change = 0.0f) {
  Scene s;
  test::SceneOptions background;
  background.count = 400;
  background.sh_degree = 0;
  background.extent = 1.5f;
  s.static_set = test::RandomGaussians(background, 21);
  for (size_t i = 0; i < s.static_set.size(); ++i) s.static_set.positions[3 * i + 2] += 1.5f;
  test::SceneOptions blob;
  blob.count = 150;
  blob.sh_degree = 0;
  blob.extent = 0.35f;
  blob.logit_lo = 1.0f;
  blob.logit_hi = 3.0f;
  blob.sh_dc = 1.5f;
  s.dynamic_set = test::RandomGaussians(blob, 22);
  s.moved_truth = Shifted(s.dynamic_set);
  for (size_t i = 0; i < s.moved_truth.size(); ++i) s.moved_truth.sh[3 * i] += red_change;
  const M4dGaussians layers[2] = {GaussianView(s.static_set), GaussianView(s.moved_truth)};
  RenderSettings settings;
  RenderContext context;
  const float target[3] = {0, 0, 0};
  for (int c = 0; c < kCameras; ++c) {
    const float angle = 1.2f * (static_cast<float>(c) / (kCameras - 1) - 0.5f);
    const float eye[3] = {4.0f * std::sin(angle), -0.5f + 0.5f * (c % 3), -4.0f * std::cos(angle)};
    const Camera camera = test::LookAtCamera(kWidth, kHeight, 70.0f, 0, 0, eye, target);
    EXPECT_TRUE(RenderForward(camera, layers, 2, settings, nullptr, &context).ok());
    Image image(kWidth, kHeight, 3);
    for (size_t i = 0; i < image.pixels.size(); ++i) {
      image.pixels[i] = std::clamp(context.color[i], 0.0f, 1.0f);
    }
    s.views.camera_indices.push_back(c);
    s.views.cameras.push_back(camera);
    s.views.images.push_back(std::move(image));
  }
  return s;
}

GridConfig SmallGrid() {
  GridConfig config;
  config.num_levels = 2;
  config.channels[0] = 4;
  config.channels[1] = 2;
  config.resolution[0] = 8;
  config.resolution[1] = 16;
  return config;
}

TEST(MotionEstimationTest, LearnsATranslation) {
  Scene s = MakeScene();
  const float steps[kMaxGridLevels] = {1.0f / 16, 1.0f / 16, 0, 0};
  MotionEstimator estimator(SmallGrid(), MlpConfig{1, 32}, steps);
  estimator.StartGop(3);
  MotionEstimationOptions options;
  options.iterations = 400;
  options.train_mlp = true;
  options.rate_weight = 1e-6;
  options.sh_degree = 0;
  options.context.seed = 4;
  MotionEstimationResult result;
  const GridBox box = DynamicGridBox(s.dynamic_set);
  ASSERT_TRUE(estimator.Estimate(s.views, s.static_set, s.dynamic_set, box, options, &result).ok());

  // Mean translation of the blob's Gaussians close to the true shift.
  double mean[3] = {0, 0, 0};
  size_t moved = 0;
  for (size_t i = 0; i < s.dynamic_set.size(); ++i) {
    if (!result.stencil.inside[i]) continue;
    ++moved;
    for (int a = 0; a < 3; ++a) mean[a] += result.motion[7 * i + a];
  }
  ASSERT_GT(moved, s.dynamic_set.size() * 9 / 10);
  for (int a = 0; a < 3; ++a) {
    mean[a] /= static_cast<double>(moved);
    EXPECT_NEAR(mean[a], kShift[a], 0.03) << "axis " << a;
  }
  // The grid is integer after training, and the MLP was kept for the GOP.
  for (int l = 0; l < 2; ++l) {
    for (float v : result.parameters.grid[l]) EXPECT_EQ(v, std::nearbyint(v));
  }
  EXPECT_EQ(estimator.mlp().layers[0].weights, result.parameters.mlp.layers[0].weights);
  EXPECT_GT(result.rate_bits, 0.0);
  // The shift is in the grid, not in the MLP's biases: zero features still do not move.
  MlpBatch batch;
  MlpForward(estimator.mlp(), Eigen::MatrixXf::Zero(SmallGrid().feature_count(), 1), &batch);
  for (int o = 0; o < 7; ++o) EXPECT_NEAR(batch.outputs.back()(o, 0), 0.0f, 1e-6f) << o;
}

TEST(MotionEstimationTest, RateTermShrinksTheGrid) {
  Scene s = MakeScene();
  const float steps[kMaxGridLevels] = {1.0f / 16, 1.0f / 16, 0, 0};
  auto nonzero_after = [&](double rate_weight, double* bits) {
    MotionEstimator estimator(SmallGrid(), MlpConfig{1, 32}, steps);
    estimator.StartGop(3);
    MotionEstimationOptions options;
    options.iterations = 200;
    options.train_mlp = true;
    options.rate_weight = rate_weight;
    options.sh_degree = 0;
    options.context.seed = 5;
    MotionEstimationResult result;
    EXPECT_TRUE(estimator
                    .Estimate(s.views, s.static_set, s.dynamic_set, DynamicGridBox(s.dynamic_set),
                              options, &result)
                    .ok());
    *bits = result.rate_bits;
    size_t nonzero = 0;
    for (int l = 0; l < 2; ++l) {
      for (float v : result.parameters.grid[l]) nonzero += v != 0.0f;
    }
    return nonzero;
  };
  double bits_low = 0, bits_high = 0;
  const size_t low = nonzero_after(1e-6, &bits_low);
  const size_t high = nonzero_after(1.0, &bits_high);
  EXPECT_LT(high, low);
  EXPECT_LT(bits_high, bits_low);
}

TEST(MotionEstimationTest, GridBoxCoversTheSetWithAMargin) {
  test::SceneOptions o;
  o.count = 1000;
  o.extent = 2.0f;
  GaussianSet set = test::RandomGaussians(o, 30);
  GridBox box = DynamicGridBox(set, 0.0f, 1.0f, 0.1f);
  for (int a = 0; a < 3; ++a) {
    float lo = 1e9f, hi = -1e9f;
    for (size_t i = 0; i < set.size(); ++i) {
      lo = std::min(lo, set.positions[3 * i + a]);
      hi = std::max(hi, set.positions[3 * i + a]);
    }
    EXPECT_NEAR(box.min[a], lo - 0.1f * (hi - lo), 1e-4f);
    EXPECT_NEAR(1.0f / box.scale[a], 1.2f * (hi - lo), 1e-4f);
  }
}

TEST(MotionEstimationTest, LearnsAColourChangeWithTheMotion) {
  const float red_change = -0.6f;
  Scene s = MakeScene(red_change);
  const float steps[kMaxGridLevels] = {1.0f / 16, 1.0f / 16, 0, 0};
  auto estimate = [&](float appearance_step, MotionEstimationResult* result) {
    MotionEstimator estimator(SmallGrid(), MlpConfig{1, 32}, steps);
    estimator.StartGop(3);
    MotionEstimationOptions options;
    options.iterations = 400;
    options.train_mlp = true;
    options.rate_weight = 1e-6;
    options.sh_degree = 0;
    options.context.seed = 4;
    options.appearance_step = appearance_step;
    return estimator.Estimate(s.views, s.static_set, s.dynamic_set, DynamicGridBox(s.dynamic_set),
                              options, result);
  };
  MotionEstimationResult without, with;
  ASSERT_TRUE(estimate(0.0f, &without).ok());
  EXPECT_TRUE(without.appearance.empty());
  const float step = 1.0f / 64;
  ASSERT_TRUE(estimate(step, &with).ok());
  ASSERT_EQ(with.appearance.size(), 3 * s.dynamic_set.size());
  // The visible blob's mean change: red as rendered, green and blue about unchanged.
  double mean[3] = {0, 0, 0};
  for (size_t i = 0; i < s.dynamic_set.size(); ++i) {
    for (int c = 0; c < 3; ++c) mean[c] += with.appearance[3 * i + c] * step;
  }
  for (double& m : mean) m /= static_cast<double>(s.dynamic_set.size());
  EXPECT_NEAR(mean[0], red_change, 0.25);
  EXPECT_NEAR(mean[1], 0.0, 0.1);
  EXPECT_NEAR(mean[2], 0.0, 0.1);
  EXPECT_GT(with.appearance_bits, 0.0);
  EXPECT_LT(with.color_loss, without.color_loss);
}

}  // namespace
}  // namespace m4d
