// Retraining growth (pipeline/retraining_growth.h): a later keyframe's retraining grows only
// what its prediction does not explain, and seeds it there.
#include "encoder/src/pipeline/retraining_growth.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "encoder/src/raster/splat_renderer.h"
#include "tests/raster/splat_test_scenes.h"

namespace m4d {
namespace {

constexpr int kWidth = 64, kHeight = 48, kViews = 4;
constexpr float kNewcomerY = 0.8f;

// Four views of `layers` around the origin.
TrainingViews Views(const std::vector<M4dGaussians>& layers) {
  TrainingViews views;
  const float target[3] = {0, 0, 0};
  RenderSettings settings;
  RenderContext context;
  for (int v = 0; v < kViews; ++v) {
    const float angle = 0.35f * static_cast<float>(v) - 0.5f;
    const float eye[3] = {4.0f * std::sin(angle), 0.3f * static_cast<float>(v % 2),
                          -4.0f * std::cos(angle)};
    views.camera_indices.push_back(v);
    views.cameras.push_back(test::LookAtCamera(kWidth, kHeight, 60.0f, 0, 0, eye, target));
    EXPECT_TRUE(RenderForward(views.cameras[v], layers.data(), static_cast<int>(layers.size()),
                              settings, nullptr, &context)
                    .ok());
    Image image(kWidth, kHeight, 3);
    for (size_t i = 0; i < image.pixels.size(); ++i) {
      image.pixels[i] = std::clamp(context.color[i], 0.0f, 1.0f);
    }
    views.images.push_back(std::move(image));
  }
  return views;
}

GaussianSet Background() {
  test::SceneOptions o;
  o.count = 150;
  o.sh_degree = 0;
  o.logit_lo = 1.0f;
  o.logit_hi = 3.0f;
  return test::RandomGaussians(o, 71);
}

// A bright, opaque cluster above the background.
GaussianSet Newcomer() {
  test::SceneOptions o;
  o.count = 40;
  o.sh_degree = 0;
  o.extent = 0.15f;
  o.logit_lo = 3.0f;
  o.logit_hi = 5.0f;
  o.sh_dc = 1.5f;
  GaussianSet set = test::RandomGaussians(o, 72);
  for (size_t i = 0; i < set.size(); ++i) set.positions[3 * i + 1] += kNewcomerY;
  return set;
}

RetrainingGrowthOptions Options() {
  RetrainingGrowthOptions o;
  o.render.sh_degree = 0;
  o.render.threads = 2;
  return o;
}

TEST(RetrainingGrowthTest, NothingGrowsWhereThePredictionExplainsTheViews) {
  const GaussianSet background = Background();
  const TrainingViews views = Views({GaussianView(background)});
  GaussianModel model;
  ASSERT_TRUE(ModelFromGaussianSet(background, 0, &model).ok());
  RetrainingGrowth growth;
  ASSERT_TRUE(GrowForUnexplained(views, Options(), &model, &growth).ok());
  EXPECT_EQ(growth.unexplained_pixels, 0u);
  EXPECT_EQ(growth.seeded, 0u);
  EXPECT_EQ(growth.cap, background.size());
  EXPECT_EQ(model.size(), background.size());
}

TEST(RetrainingGrowthTest, SeedsWhatAppearedWhereItIs) {
  const GaussianSet background = Background(), newcomer = Newcomer();
  const TrainingViews views = Views({GaussianView(background), GaussianView(newcomer)});
  GaussianModel model;
  ASSERT_TRUE(ModelFromGaussianSet(background, 0, &model).ok());
  RetrainingGrowthOptions options = Options();
  RetrainingGrowth growth;
  ASSERT_TRUE(GrowForUnexplained(views, options, &model, &growth).ok());
  // The cluster covers a few hundred pixels of each view, not the whole views.
  EXPECT_GT(growth.unexplained_pixels, 100u * kViews);
  EXPECT_LT(growth.unexplained_pixels, kWidth * kHeight * kViews / 3u);
  const size_t bound = growth.unexplained_pixels / 4;  // 0.25 per pixel
  EXPECT_EQ(growth.cap, background.size() + bound);
  EXPECT_GT(growth.seeded, 0u);
  EXPECT_LE(growth.seeded, bound / 2);
  ASSERT_EQ(model.size(), background.size() + growth.seeded);
  // The kept Gaussians come first, unchanged. The seeds lie on rays through the cluster's
  // pixels, inside the background's box (within 1 of the origin), at the depth the views
  // agree on: most within 1 of the cluster (measured: 66 of 95, 59 when the rays ran 50
  // extents out; the depth is coarse with four views 0.35 rad apart at 64x48).
  EXPECT_TRUE(std::equal(background.positions.begin(), background.positions.end(),
                         model.positions.begin()));
  size_t near = 0;
  for (size_t i = background.size(); i < model.size(); ++i) {
    const float* p = &model.positions[3 * i];
    for (int a = 0; a < 3; ++a) EXPECT_LE(std::abs(p[a]), 1.0f) << i;
    near += std::hypot(p[0], p[1] - kNewcomerY, p[2]) < 1.0f ? 1 : 0;
  }
  EXPECT_GT(near, growth.seeded / 2) << near << " of " << growth.seeded;
  // Seeds start nearly transparent, so that they do not veil the prediction.
  for (size_t i = background.size(); i < model.size(); ++i) {
    const float opacity = 1.0f / (1.0f + std::exp(-model.opacity_logits[i]));
    EXPECT_NEAR(opacity, options.seed_opacity, 1e-4f);
  }
  options.gaussians_per_pixel = -1.0f;
  EXPECT_EQ(GrowForUnexplained(views, options, &model, &growth).code(), M4D_ERR_INVALID_ARG);
}

}  // namespace
}  // namespace m4d
