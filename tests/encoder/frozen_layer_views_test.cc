// A render given its first layer's projection (FrozenLayerViews, RenderForward with
// first_layer) is the render that projects every layer, bit for bit, gradients included; the
// frozen layer's render alone is its plain render.
#include "encoder/src/train/frozen_layer_views.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "encoder/src/raster/render_context.h"
#include "encoder/src/raster/splat_backward.h"
#include "encoder/src/raster/splat_renderer.h"
#include "tests/raster/splat_test_scenes.h"

namespace m4d {
namespace {

struct Result {
  std::vector<float> color, alpha, positions_grad;
};

// Renders the two layers (the first frozen) with or without the given projection and runs
// the backward pass with dL/dcolour = 1.
Result RenderBoth(const Camera& camera, const M4dGaussians* layers, const RenderSettings& settings,
                  const ProjectedSplats* first_layer) {
  RenderContext ctx;
  EXPECT_TRUE(RenderForward(camera, layers, 2, settings, nullptr, first_layer, &ctx).ok());
  const size_t n = layers[1].count;
  std::vector<float> p(3 * n), sc(3 * n), q(4 * n), o(n),
      sh(n * 3 * ShCoefficients(layers[1].sh_degree));
  LayerGradients out[2];
  out[1] = {p.data(), sc.data(), q.data(), o.data(), sh.data()};
  SplatGradients gradients;
  gradients.layers = out;
  gradients.layer_count = 2;
  BackwardWorkspace ws;
  const std::vector<float> ones(ctx.color.size(), 1.0f);
  EXPECT_TRUE(RenderBackward(ones.data(), nullptr, &ctx, gradients, &ws).ok());
  return {ctx.color, ctx.alpha, p};
}

class FrozenLayerViewsTest : public ::testing::TestWithParam<int> {};

TEST_P(FrozenLayerViewsTest, GivenProjectionRendersTheSameBitForBit) {
  test::SceneOptions background;
  background.count = 800;
  background.sh_degree = 2;
  const GaussianSet static_set = test::RandomGaussians(background, 5);
  test::SceneOptions cluster = background;
  cluster.count = 40;
  cluster.extent = 0.3f;
  const GaussianSet dynamic_set = test::RandomGaussians(cluster, 6);
  const M4dGaussians layers[2] = {GaussianView(static_set), GaussianView(dynamic_set)};
  const Camera cameras[2] = {test::TestCamera(160, 120), test::TestCamera(96, 200)};
  RenderSettings settings;
  settings.sh_degree = 1;
  settings.focus_layer = GetParam();
  FrozenLayerViews frozen(layers[0], settings, 2);
  for (int v : {1, 0, 1}) {
    const ProjectedSplats* given = nullptr;
    ASSERT_TRUE(frozen.Projection(v, cameras[v], &given).ok());
    ASSERT_EQ(given->size(), static_set.size());
    const Result expected = RenderBoth(cameras[v], layers, settings, nullptr);
    const Result got = RenderBoth(cameras[v], layers, settings, given);
    EXPECT_EQ(got.color, expected.color);
    EXPECT_EQ(got.alpha, expected.alpha);
    EXPECT_EQ(got.positions_grad, expected.positions_grad);
    EXPECT_GT(*std::max_element(got.alpha.begin(), got.alpha.end()), 0.5f);

    const Image* alone = nullptr;
    ASSERT_TRUE(frozen.Render(v, cameras[v], &alone).ok());
    RenderSettings plain = settings;
    plain.focus_layer = -1;
    RenderContext ctx;
    ASSERT_TRUE(RenderForward(cameras[v], layers, 1, plain, nullptr, &ctx).ok());
    EXPECT_EQ(alone->pixels, ctx.color);
    EXPECT_EQ(alone->width, cameras[v].width);
  }
}

INSTANTIATE_TEST_SUITE_P(WholeImageAndFocus, FrozenLayerViewsTest, ::testing::Values(-1, 1));

TEST(FrozenLayerViewsTest, MismatchesAreRejected) {
  test::SceneOptions options;
  const GaussianSet a = test::RandomGaussians(options, 1);
  options.count = 7;
  const GaussianSet b = test::RandomGaussians(options, 2);
  const Camera camera = test::TestCamera(64, 48);
  FrozenLayerViews frozen(GaussianView(a), RenderSettings(), 1);
  const ProjectedSplats* given = nullptr;
  const Image* render = nullptr;
  EXPECT_EQ(frozen.Projection(1, camera, &given).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(frozen.Projection(-1, camera, &given).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(frozen.Render(1, camera, &render).code(), M4D_ERR_INVALID_ARG);
  ASSERT_TRUE(frozen.Projection(0, camera, &given).ok());
  // A projection of another layer's size.
  const M4dGaussians layers[2] = {GaussianView(b), GaussianView(a)};
  RenderContext ctx;
  EXPECT_EQ(RenderForward(camera, layers, 2, RenderSettings(), nullptr, given, &ctx).code(),
            M4D_ERR_INVALID_ARG);
  EXPECT_EQ(RenderForward(camera, layers, 0, RenderSettings(), nullptr, given, &ctx).code(),
            M4D_ERR_INVALID_ARG);
  EXPECT_FALSE(ctx.valid);
}

}  // namespace
}  // namespace m4d
