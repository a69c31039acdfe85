// Motion estimation's batch of views per step: rendered one per thread, the same gradients as
// on one thread, and their mean over the batch.
#include "encoder/src/motion/view_batch_gradients.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "encoder/src/raster/splat_renderer.h"
#include "tests/raster/splat_test_scenes.h"

namespace m4d {
namespace {

struct Scene {
  GaussianSet static_set, dynamic_set;
  TrainingViews views;
};

// A static background and a small dynamic cluster, seen from three cameras whose images show
// the cluster moved.
Scene MakeScene() {
  Scene s;
  test::SceneOptions background;
  background.count = 600;
  background.sh_degree = 1;
  s.static_set = test::RandomGaussians(background, 11);
  test::SceneOptions cluster = background;
  cluster.count = 30;
  cluster.extent = 0.25f;
  s.dynamic_set = test::RandomGaussians(cluster, 12);
  GaussianSet moved = s.dynamic_set;
  for (size_t i = 0; i < moved.size(); ++i) moved.positions[3 * i + 1] += 0.04f;
  const M4dGaussians layers[2] = {GaussianView(s.static_set), GaussianView(moved)};
  const float target[3] = {0.0f, 0.0f, 0.0f};
  for (int v = 0; v < 3; ++v) {
    const float eye[3] = {-1.0f + v, 0.2f * v, -4.0f};
    const Camera camera = test::LookAtCamera(128 + 16 * v, 96, 150.0f, 3.0f, -2.0f, eye, target);
    RenderContext ctx;
    EXPECT_TRUE(RenderForward(camera, layers, 2, RenderSettings(), nullptr, &ctx).ok());
    Image image(camera.width, camera.height, 3);
    image.pixels = ctx.color;
    s.views.camera_indices.push_back(v);
    s.views.cameras.push_back(camera);
    s.views.images.push_back(image);
  }
  return s;
}

ViewBatchResult Gradients(const Scene& s, int threads, const std::vector<int>& batch) {
  RenderSettings settings;
  settings.threads = threads;
  settings.sh_degree = 1;
  FrozenLayerViews frozen(GaussianView(s.static_set), settings, s.views.size());
  ViewBatchGradients gradients(s.views, settings, kDefaultSsimWeight, &frozen);
  const M4dGaussians layers[2] = {GaussianView(s.static_set), GaussianView(s.dynamic_set)};
  ViewBatchResult result;
  EXPECT_TRUE(gradients.Compute(layers, batch, true, &result).ok());
  return result;
}

TEST(ViewBatchGradientsTest, ViewsOnTwoThreadsGiveTheOneThreadResultBitForBit) {
  const Scene s = MakeScene();
  const ViewBatchResult one = Gradients(s, 1, {2, 0, 1});
  const ViewBatchResult two = Gradients(s, 2, {2, 0, 1});
  EXPECT_EQ(one.positions, two.positions);
  EXPECT_EQ(one.rotations, two.rotations);
  EXPECT_EQ(one.dc, two.dc);
  EXPECT_EQ(one.losses, two.losses);
  ASSERT_EQ(one.losses.size(), 3u);
  EXPECT_GT(*std::max_element(one.positions.begin(), one.positions.end()), 0.0f);
}

TEST(ViewBatchGradientsTest, BatchIsTheMeanOfItsViews) {
  const Scene s = MakeScene();
  const ViewBatchResult a = Gradients(s, 2, {0});
  const ViewBatchResult b = Gradients(s, 2, {1});
  const ViewBatchResult both = Gradients(s, 2, {0, 1});
  ASSERT_EQ(both.losses.size(), 2u);
  EXPECT_EQ(both.losses[0], a.losses[0]);
  EXPECT_EQ(both.losses[1], b.losses[0]);
  float largest = 0, worst = 0;
  for (size_t k = 0; k < both.positions.size(); ++k) {
    const float mean = 0.5f * (a.positions[k] + b.positions[k]);
    largest = std::max(largest, std::fabs(mean));
    worst = std::max(worst, std::fabs(both.positions[k] - mean));
  }
  ASSERT_GT(largest, 0.0f);
  EXPECT_LT(worst, 1e-6f * largest);
  EXPECT_NE(a.positions, b.positions);
}

TEST(ViewBatchGradientsTest, ViewOutOfRangeIsAnError) {
  const Scene s = MakeScene();
  RenderSettings settings;
  FrozenLayerViews frozen(GaussianView(s.static_set), settings, s.views.size());
  ViewBatchGradients gradients(s.views, settings, kDefaultSsimWeight, &frozen);
  const M4dGaussians layers[2] = {GaussianView(s.static_set), GaussianView(s.dynamic_set)};
  ViewBatchResult result;
  EXPECT_EQ(gradients.Compute(layers, {0, 3}, false, &result).code(), M4D_ERR_INVALID_ARG);
}

}  // namespace
}  // namespace m4d
