// Importance pruning (train/importance_pruning.h): blending weights against the rendered
// alpha, occlusion, and which Gaussians KeepImportant removes.
#include "encoder/src/train/importance_pruning.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "encoder/src/raster/splat_renderer.h"
#include "sdk/src/render/sh_evaluation.h"
#include "tests/raster/splat_test_scenes.h"

namespace m4d {
namespace {

constexpr int kWidth = 64, kHeight = 48;

// Gaussian i of a degree-0 model: white (colour 1), isotropic, at `position`.
void SetGaussian(size_t i, const float position[3], float log_scale, float opacity_logit,
                 GaussianModel* model) {
  for (int a = 0; a < 3; ++a) {
    model->positions[3 * i + a] = position[a];
    model->log_scales[3 * i + a] = log_scale;
    model->sh[3 * i + a] = 0.5f / kShC0;
  }
  model->rotations[4 * i] = 1.0f;
  model->opacity_logits[i] = opacity_logit;
}

TrainingViews OneView() {
  const float eye[3] = {0, 0, -4}, target[3] = {0, 0, 0};
  TrainingViews views;
  views.camera_indices = {0};
  views.cameras = {test::LookAtCamera(kWidth, kHeight, 60.0f, 0, 0, eye, target)};
  views.images = {Image(kWidth, kHeight, 3)};
  return views;
}

RenderSettings Settings() {
  RenderSettings settings;
  settings.threads = 2;
  settings.sh_degree = 0;
  return settings;
}

TEST(ImportancePruningTest, WeightOfALoneGaussianIsItsRenderedAlpha) {
  GaussianModel model;
  model.sh_degree = 0;
  model.Resize(1);
  const float centre[3] = {0.1f, -0.05f, 0.0f};
  SetGaussian(0, centre, std::log(0.2f), 0.5f, &model);
  const TrainingViews views = OneView();
  RenderContext context;
  BackwardWorkspace workspace;
  std::vector<double> weights;
  ASSERT_TRUE(BlendingWeights(model, views, Settings(), &context, &workspace, &weights).ok());
  ASSERT_EQ(weights.size(), 1u);
  // White on black: each pixel's red is the Gaussian's alpha there.
  const M4dGaussians layer = GaussianView(model);
  ASSERT_TRUE(RenderForward(views.cameras[0], &layer, 1, Settings(), nullptr, &context).ok());
  double alpha = 0;
  for (size_t p = 0; p < context.color.size(); p += 3) alpha += context.color[p];
  EXPECT_GT(alpha, 10.0);
  EXPECT_NEAR(weights[0], alpha, 1e-4 * alpha);
}

TEST(ImportancePruningTest, HiddenAndUnseenGaussiansWeighLittle) {
  GaussianModel model;
  model.sh_degree = 0;
  model.Resize(3);
  const float front[3] = {0, 0, 0}, behind[3] = {0, 0, 1.0f}, aside[3] = {30.0f, 0, 0};
  SetGaussian(0, front, std::log(0.4f), 6.0f, &model);   // opaque, covers the one behind
  SetGaussian(1, behind, std::log(0.1f), 6.0f, &model);  // as opaque, but hidden
  SetGaussian(2, aside, std::log(0.1f), 6.0f, &model);   // outside the view
  RenderContext context;
  BackwardWorkspace workspace;
  std::vector<double> weights;
  ASSERT_TRUE(BlendingWeights(model, OneView(), Settings(), &context, &workspace, &weights).ok());
  ASSERT_EQ(weights.size(), 3u);
  EXPECT_GT(weights[0], 100.0);
  EXPECT_LT(weights[1], 0.02 * weights[0]);
  EXPECT_EQ(weights[2], 0.0);
  const std::vector<uint8_t> keep = KeepImportant(weights, 0.05);
  EXPECT_EQ(keep, (std::vector<uint8_t>{1, 0, 0}));
}

TEST(ImportancePruningTest, KeepImportantRemovesTheLeastUpToTheShare) {
  const std::vector<double> weights = {5.0, 0.1, 3.0, 0.2, 0.2, 1.5};  // total 10
  EXPECT_EQ(KeepImportant(weights, 0.0), (std::vector<uint8_t>{1, 1, 1, 1, 1, 1}));
  EXPECT_EQ(KeepImportant(weights, 0.015), (std::vector<uint8_t>{1, 0, 1, 1, 1, 1}));
  // 0.1 + 0.2 = 0.3 of a budget of 0.4: the second 0.2 would pass it.
  EXPECT_EQ(KeepImportant(weights, 0.04), (std::vector<uint8_t>{1, 0, 1, 0, 1, 1}));
  // 0.1 + 0.2 + 0.2 + 1.5 = 2.0 of 2.1.
  EXPECT_EQ(KeepImportant(weights, 0.21), (std::vector<uint8_t>{1, 0, 1, 0, 0, 0}));
  EXPECT_TRUE(KeepImportant({}, 0.5).empty());
}

TEST(ImportancePruningTest, KeepImportantRemovesWhatCoversLessThanTheMinimum) {
  const std::vector<double> weights = {5.0, 0.1, 3.0, 0.2, 0.2, 1.5};
  // Below 0.25 pixels: 0.1 and both 0.2, whatever the share.
  EXPECT_EQ(KeepImportant(weights, 0.0, 0.25), (std::vector<uint8_t>{1, 0, 1, 0, 0, 1}));
  EXPECT_EQ(KeepImportant(weights, 0.015, 0.25), (std::vector<uint8_t>{1, 0, 1, 0, 0, 1}));
  // A share past the minimum removes the next ones too; a weight at the minimum stays.
  EXPECT_EQ(KeepImportant(weights, 0.21, 0.25), (std::vector<uint8_t>{1, 0, 1, 0, 0, 0}));
  EXPECT_EQ(KeepImportant(weights, 0.0, 0.2), (std::vector<uint8_t>{1, 0, 1, 1, 1, 1}));
  // The minimum removes at most a third here (two of six), the least important first; the
  // measured share is not bounded.
  EXPECT_EQ(KeepImportant(weights, 0.0, 0.25, 1.0 / 3), (std::vector<uint8_t>{1, 0, 1, 0, 1, 1}));
  EXPECT_EQ(KeepImportant(weights, 0.21, 0.25, 1.0 / 3), (std::vector<uint8_t>{1, 0, 1, 0, 0, 0}));
}

}  // namespace
}  // namespace m4d
