// Lookahead decoupling end to end (paper 3.2, 4.1): a background and a blob that moves by
// frame t1; the keyframe model (the truth of frame 0) is split into static and dynamic.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "decoupling/lookahead_decoupling.h"
#include "render/splat_renderer.h"
#include "splat_test_scenes.h"
#include "train/training_views.h"

namespace m4d {
namespace {

constexpr int kWidth = 80, kHeight = 60, kCameras = 6;

TEST(LookaheadDecouplingTest, SeparatesTheMovingBlobFromTheBackground) {
  test::SceneOptions background;
  background.count = 300;
  background.sh_degree = 0;
  background.extent = 1.5f;
  background.logit_lo = 1.0f;
  background.logit_hi = 3.0f;
  GaussianSet static_set = test::RandomGaussians(background, 41);
  for (size_t i = 0; i < static_set.size(); ++i) static_set.positions[3 * i + 2] += 2.0f;
  test::SceneOptions blob;
  blob.count = 100;
  blob.sh_degree = 0;
  blob.extent = 0.3f;
  blob.logit_lo = 2.0f;
  blob.logit_hi = 4.0f;
  blob.sh_dc = 1.5f;
  GaussianSet dynamic_set = test::RandomGaussians(blob, 42);
  GaussianSet moved = dynamic_set;
  for (size_t i = 0; i < moved.size(); ++i) moved.positions[3 * i] += 0.15f;

  // Frame t1's views: the background and the moved blob.
  TrainingViews views;
  const GaussianLayerView layers[2] = {LayerView(static_set), LayerView(moved)};
  RenderSettings settings;
  RenderContext context;
  const float target[3] = {0, 0, 0};
  for (int c = 0; c < kCameras; ++c) {
    const float angle = 1.0f * (static_cast<float>(c) / (kCameras - 1) - 0.5f);
    const float eye[3] = {4.0f * std::sin(angle), -0.4f + 0.4f * (c % 3), -4.0f * std::cos(angle)};
    const Camera camera = test::LookAtCamera(kWidth, kHeight, 90.0f, 0, 0, eye, target);
    ASSERT_TRUE(RenderForward(camera, layers, 2, settings, nullptr, &context).ok());
    Image image(kWidth, kHeight, 3);
    for (size_t i = 0; i < image.pixels.size(); ++i) {
      image.pixels[i] = std::clamp(context.color[i], 0.0f, 1.0f);
    }
    views.camera_indices.push_back(c);
    views.cameras.push_back(camera);
    views.images.push_back(std::move(image));
  }

  // The keyframe model: both sets of frame 0, background first.
  GaussianSet all = static_set;
  const size_t ns = static_set.size();
  all.Resize(ns + dynamic_set.size());
  std::copy(dynamic_set.positions.begin(), dynamic_set.positions.end(), &all.positions[3 * ns]);
  std::copy(dynamic_set.log_scales.begin(), dynamic_set.log_scales.end(), &all.log_scales[3 * ns]);
  std::copy(dynamic_set.rotations.begin(), dynamic_set.rotations.end(), &all.rotations[4 * ns]);
  std::copy(dynamic_set.opacity_logits.begin(), dynamic_set.opacity_logits.end(),
            &all.opacity_logits[ns]);
  std::copy(dynamic_set.sh.begin(), dynamic_set.sh.end(), &all.sh[3 * ns]);
  GaussianModel keyframe;
  ASSERT_TRUE(ModelFromGaussianSet(all, 0, &keyframe).ok());

  DecouplingOptions options;
  options.fine_tune_iterations = 300;
  // A 0.15 shift seen from distance 4 with a 90 px focal moves about 3 px: delta ~ 0.8.
  options.thresholds.displacement = 0.3f;
  options.thresholds.scale_change = 0.5f;
  options.thresholds.error = 0.2f;
  options.seed = 1;
  DecouplingResult result;
  ASSERT_TRUE(DecoupleKeyframe(keyframe, views, 6.0f, options, &result).ok());
  size_t blob_dynamic = 0, background_dynamic = 0;
  for (size_t i = 0; i < all.size(); ++i) {
    (i < ns ? background_dynamic : blob_dynamic) += result.dynamic[i];
  }
  EXPECT_GT(blob_dynamic, dynamic_set.size() * 8 / 10)
      << result.initially_dynamic << " " << result.refined_dynamic;
  EXPECT_LT(background_dynamic, ns / 10) << blob_dynamic;
  EXPECT_EQ(result.dynamic_model.size() + result.static_model.size(), all.size());
  EXPECT_EQ(result.dynamic_model.size(), blob_dynamic + background_dynamic);
  // The sets are the keyframe's Gaussians, not the fine-tuned ones.
  EXPECT_EQ(result.static_model.positions[0], all.positions[0]);
}

}  // namespace
}  // namespace m4d
