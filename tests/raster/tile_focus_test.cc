// A render focused on the dynamic layer (encoder/src/raster/tile_focus.h) and its loss
// (metrics/focused_loss.h) give the dynamic layer the gradients of the whole image's loss, for
// the work of the tiles it covers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "encoder/src/image/image.h"
#include "encoder/src/metrics/focused_loss.h"
#include "encoder/src/metrics/photometric_loss.h"
#include "encoder/src/raster/render_context.h"
#include "encoder/src/raster/splat_backward.h"
#include "encoder/src/raster/splat_renderer.h"
#include "tests/raster/splat_test_scenes.h"

namespace m4d {
namespace {

struct Scene {
  Camera camera = test::TestCamera(192, 144);
  GaussianSet static_set, dynamic_set;
  Image target;
};

Image Render(const Camera& camera, const M4dGaussians* layers, int count,
             const RenderSettings& settings, RenderContext* ctx) {
  EXPECT_TRUE(RenderForward(camera, layers, count, settings, nullptr, ctx).ok());
  Image image(camera.width, camera.height, 3);
  image.pixels = ctx->color;
  return image;
}

// A static background and a small dynamic cluster; the target shows the cluster moved.
Scene MakeScene() {
  Scene s;
  test::SceneOptions background;
  background.count = 1500;
  background.sh_degree = 1;
  s.static_set = test::RandomGaussians(background, 71);
  test::SceneOptions cluster = background;
  cluster.count = 50;
  cluster.extent = 0.2f;
  s.dynamic_set = test::RandomGaussians(cluster, 72);
  GaussianSet moved = s.dynamic_set;
  for (size_t i = 0; i < moved.size(); ++i) moved.positions[3 * i] += 0.03f;
  const M4dGaussians layers[2] = {GaussianView(s.static_set), GaussianView(moved)};
  RenderContext ctx;
  s.target = Render(s.camera, layers, 2, RenderSettings(), &ctx);
  return s;
}

enum class Focus { kNone, kMargin, kStaticAround };

// The dynamic layer's position gradients with the static layer frozen: from the whole image,
// a focus grown by a tile, or a focus without margin whose loss reads the static layer's
// render around it.
std::vector<float> DynamicGradients(const Scene& s, Focus mode, RenderContext* ctx,
                                    Image* rendered) {
  RenderSettings settings;
  const bool focused = mode != Focus::kNone;
  if (focused) settings.focus_layer = 1;
  if (mode == Focus::kStaticAround) settings.focus_margin = 0;
  const M4dGaussians layers[2] = {GaussianView(s.static_set), GaussianView(s.dynamic_set)};
  *rendered = Render(s.camera, layers, 2, settings, ctx);
  PhotometricLossValue value;
  Image grad;
  if (focused) {
    RenderContext static_ctx;
    const Image static_render = Render(s.camera, layers, 1, RenderSettings(), &static_ctx);
    const Image* unfocused = mode == Focus::kStaticAround ? &static_render : nullptr;
    FocusedLoss loss;
    EXPECT_TRUE(loss.Evaluate(*rendered, s.target, ctx->focus, unfocused, &value, &grad).ok());
  } else {
    PhotometricLoss loss;
    EXPECT_TRUE(loss.Evaluate(*rendered, s.target, &value, &grad).ok());
  }
  const size_t n = s.dynamic_set.size();
  std::vector<float> p(3 * n), sc(3 * n), q(4 * n), o(n), sh(s.dynamic_set.sh.size());
  LayerGradients out[2];
  out[1] = {p.data(), sc.data(), q.data(), o.data(), sh.data()};
  SplatGradients gradients;
  gradients.layers = out;
  gradients.layer_count = 2;
  BackwardWorkspace ws;
  EXPECT_TRUE(RenderBackward(grad.pixels.data(), nullptr, ctx, gradients, &ws).ok());
  return p;
}

class TileFocusTest : public ::testing::TestWithParam<Focus> {};

TEST_P(TileFocusTest, FocusedRenderGivesTheDynamicLayerTheWholeImagesGradients) {
  const Scene s = MakeScene();
  RenderContext full_ctx, focus_ctx;
  Image full, focused;
  const std::vector<float> whole = DynamicGradients(s, Focus::kNone, &full_ctx, &full);
  const std::vector<float> part = DynamicGradients(s, GetParam(), &focus_ctx, &focused);
  float largest = 0, worst = 0;
  for (float g : whole) largest = std::max(largest, std::fabs(g));
  ASSERT_GT(largest, 0.0f);
  for (size_t k = 0; k < whole.size(); ++k) worst = std::max(worst, std::fabs(whole[k] - part[k]));
  EXPECT_LT(worst, 1e-4f * largest);

  // Only some tiles were rendered, and those are the whole render's pixels bit for bit.
  const TileFocus& focus = focus_ctx.focus;
  ASSERT_FALSE(focus.all);
  const size_t tiles = focus.mask.size();
  const size_t rendered = static_cast<size_t>(std::count(focus.mask.begin(), focus.mask.end(), 1));
  EXPECT_GT(rendered, 0u);
  EXPECT_LT(rendered, tiles / 2);
  for (size_t t = 0; t < tiles; ++t) {
    const int tx = static_cast<int>(t % focus.tiles_x), ty = static_cast<int>(t / focus.tiles_x);
    const float* a = &full.at(16 * tx, 16 * ty, 0);
    const float* b = &focused.at(16 * tx, 16 * ty, 0);
    if (focus.mask[t]) {
      EXPECT_EQ(a[0], b[0]);
    } else {
      EXPECT_EQ(b[0], 0.0f);  // the background
    }
  }
}

INSTANTIATE_TEST_SUITE_P(MarginOrStaticAround, TileFocusTest,
                         ::testing::Values(Focus::kMargin, Focus::kStaticAround),
                         [](const ::testing::TestParamInfo<Focus>& param) {
                           return param.param == Focus::kMargin ? "Margin" : "StaticAround";
                         });

TEST_P(TileFocusTest, NothingInFocusRendersNothing) {
  Scene s = MakeScene();
  s.dynamic_set.Resize(0);
  RenderContext ctx;
  Image rendered;
  DynamicGradients(s, GetParam(), &ctx, &rendered);
  EXPECT_TRUE(ctx.focus.rect.empty());
  EXPECT_EQ(*std::max_element(rendered.pixels.begin(), rendered.pixels.end()), 0.0f);
}

}  // namespace
}  // namespace m4d
