// The forward rasterizer (sdk/src/render): analytic single-Gaussian images, SH colour,
// background, culling, depth order, thread independence, agreement with a brute-force
// double-precision renderer, per-Gaussian blend weights, and rejection of bad input.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "encoder/src/raster/render_context.h"
#include "encoder/src/raster/splat_renderer.h"
#include "sdk/src/layers/gaussian_set.h"
#include "sdk/src/render/camera.h"
#include "sdk/src/render/lanes.h"
#include "sdk/src/render/sh_evaluation.h"
#include "sdk/src/render/splat_alpha.h"
#include "tests/raster/reference_splat_renderer.h"
#include "tests/raster/splat_test_scenes.h"

namespace m4d {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

Camera AxisCamera(int width, int height, float focal, float cx, float cy) {
  Camera camera;
  camera.width = width;
  camera.height = height;
  camera.fx = camera.fy = focal;
  camera.cx = cx;
  camera.cy = cy;
  return camera;
}

// One Gaussian with the given camera-space position (identity camera), isotropic scale,
// opacity logit and degree-0 colour coefficients.
GaussianSet OneGaussian(float x, float y, float z, float log_scale, float logit,
                        const float sh0[3]) {
  GaussianSet set;
  set.sh_degree = 0;
  set.Resize(1);
  set.positions = {x, y, z};
  set.log_scales = {log_scale, log_scale, log_scale};
  set.rotations = {1, 0, 0, 0};
  set.opacity_logits = {logit};
  set.sh = {sh0[0], sh0[1], sh0[2]};
  return set;
}

Status Render(const Camera& camera, const std::vector<GaussianSet>& sets,
              const RenderSettings& settings, RenderContext* ctx,
              const float* error_image = nullptr) {
  const std::vector<M4dGaussians> views = test::Views(sets);
  return RenderForward(camera, views.data(), static_cast<int>(views.size()), settings, error_image,
                       ctx);
}

TEST(SplatRendererTest, SingleIsotropicGaussianIsTheAnalytic2DGaussian) {
  // On the optical axis of an off-centre principal point: the 2D covariance is
  // (s f / z)^2 I + 0.3 I, centred at (cx, cy).
  const float cx = 27.3f, cy = 17.8f, f = 40.0f, z = 3.0f, s = 0.15f;
  const Camera camera = AxisCamera(48, 40, f, cx, cy);
  const float sh0[3] = {0.8f, -0.3f, 0.1f};
  const float logit = 0.4f;
  RenderContext ctx;
  RenderSettings settings;
  settings.background[0] = 0.25f;
  ASSERT_TRUE(Render(camera, {OneGaussian(0, 0, z, std::log(s), logit, sh0)}, settings, &ctx).ok());

  const double var = std::pow(double{s} * f / z, 2) + 0.3;
  const double opacity = 1 / (1 + std::exp(-double{logit}));
  // The reference's largest eigenvalue: mid + sqrt(max(0.1, mid^2 - det)), here var + sqrt(0.1).
  const double radius = std::ceil(3 * std::sqrt(var + std::sqrt(0.1)));
  EXPECT_EQ(ctx.splats.radius[0], radius);
  EXPECT_FLOAT_EQ(ctx.splats.mean_x[0], cx);
  EXPECT_FLOAT_EQ(ctx.splats.mean_y[0], cy);
  EXPECT_FLOAT_EQ(ctx.splats.depth[0], z);
  int checked = 0;
  for (int py = 0; py < camera.height; ++py) {
    for (int px = 0; px < camera.width; ++px) {
      const double dx = px + 0.5 - cx, dy = py + 0.5 - cy;
      double alpha = opacity * std::exp(-0.5 * (dx * dx + dy * dy) / var);
      const bool inside = std::fabs(dx) <= radius && std::fabs(dy) <= radius;
      if (!inside || alpha < 1.0 / 255 - 1e-6) alpha = 0;
      if (std::fabs(alpha - 1.0 / 255) < 1e-5) continue;  // at the skip threshold
      const size_t p = static_cast<size_t>(py) * camera.width + px;
      ASSERT_NEAR(ctx.alpha[p], alpha, 2e-6) << px << "," << py;
      for (int c = 0; c < 3; ++c) {
        const double colour = std::max(0.0, sh0[c] * double{kShC0} + 0.5);
        const double bg = settings.background[c];
        ASSERT_NEAR(ctx.color[3 * p + c], colour * alpha + (1 - alpha) * bg, 2e-6);
      }
      checked += alpha > 0;
    }
  }
  EXPECT_GT(checked, 100);
}

TEST(SplatRendererTest, DegreeZeroColourIsShTimesC0PlusHalfClampedAtZero) {
  const float eye[3] = {0, 0, -4}, target[3] = {0, 0, 0};
  const Camera camera = test::LookAtCamera(32, 24, 30, 0, 0, eye, target);
  test::SceneOptions o;
  o.count = 30;
  o.sh_degree = 0;
  o.sh_dc = 3.0f;  // some channels go negative
  o.extent = 0.5f;
  const GaussianSet set = test::RandomGaussians(o, 7);
  RenderContext ctx;
  ASSERT_TRUE(Render(camera, {set}, RenderSettings(), &ctx).ok());
  int clamped = 0;
  for (size_t i = 0; i < set.size(); ++i) {
    if (ctx.splats.radius[i] == 0) continue;
    for (int c = 0; c < 3; ++c) {
      const float expected = set.sh[3 * i + c] * kShC0 + 0.5f;
      EXPECT_EQ(ctx.splats.color[c][i], std::max(0.0f, expected));
      EXPECT_EQ((ctx.splats.color_clamped[i] >> c) & 1, expected < 0 ? 1 : 0);
      clamped += expected < 0;
    }
  }
  EXPECT_GT(clamped, 0);
}

TEST(SplatRendererTest, ActiveShDegreeLimitsEvaluation) {
  const Camera camera = test::TestCamera(40, 30);
  test::SceneOptions o;
  o.sh_degree = 3;
  const GaussianSet set = test::RandomGaussians(o, 11);
  GaussianSet dc = set;  // the same Gaussians with only their DC coefficients
  dc.sh_degree = 0;
  dc.sh.resize(3 * set.size());
  for (size_t i = 0; i < set.size(); ++i) {
    for (int c = 0; c < 3; ++c) dc.sh[3 * i + c] = set.sh[48 * i + c];
  }
  RenderSettings settings;
  settings.sh_degree = 0;
  RenderContext a, b;
  ASSERT_TRUE(Render(camera, {set}, settings, &a).ok());
  ASSERT_TRUE(Render(camera, {dc}, RenderSettings(), &b).ok());
  EXPECT_EQ(a.color, b.color);
  settings.sh_degree = 3;
  ASSERT_TRUE(Render(camera, {set}, settings, &a).ok());
  EXPECT_NE(a.color, b.color);
}

TEST(SplatRendererTest, BackgroundIsCompositedWithFinalTransmittance) {
  const Camera camera = test::TestCamera(40, 30);
  const GaussianSet set = test::RandomGaussians(test::SceneOptions(), 3);
  RenderSettings settings;
  RenderContext black, coloured;
  ASSERT_TRUE(Render(camera, {set}, settings, &black).ok());
  const float bg[3] = {0.2f, 0.7f, 1.0f};
  std::copy(bg, bg + 3, settings.background);
  ASSERT_TRUE(Render(camera, {set}, settings, &coloured).ok());
  int uncovered = 0;
  for (size_t p = 0; p < black.alpha.size(); ++p) {
    EXPECT_EQ(black.alpha[p], coloured.alpha[p]);
    const float t = 1.0f - black.alpha[p];
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(coloured.color[3 * p + c], black.color[3 * p + c] + t * bg[c], 1e-6f);
    }
    if (black.alpha[p] == 0) {
      ++uncovered;
      for (int c = 0; c < 3; ++c) EXPECT_EQ(coloured.color[3 * p + c], bg[c]);
    }
  }
  EXPECT_GT(uncovered, 0);

  // No Gaussians at all: the background everywhere.
  ASSERT_TRUE(RenderForward(camera, nullptr, 0, settings, nullptr, &coloured).ok());
  for (size_t p = 0; p < coloured.alpha.size(); ++p) {
    EXPECT_EQ(coloured.alpha[p], 0.0f);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(coloured.color[3 * p + c], bg[c]);
  }
}

TEST(SplatRendererTest, GaussiansBehindTheCameraOrTheNearPlaneAreCulled) {
  const Camera camera = AxisCamera(32, 32, 30, 16, 16);
  const float sh0[3] = {1, 1, 1};
  // Large enough to cover the image if it were projected with |z|.
  for (float z : {-3.0f, -0.5f, 0.0f, 0.1f, 0.2f}) {
    RenderContext ctx;
    ASSERT_TRUE(
        Render(camera, {OneGaussian(0, 0, z, std::log(0.5f), 3, sh0)}, RenderSettings(), &ctx)
            .ok());
    EXPECT_EQ(ctx.splats.radius[0], 0) << z;
    for (float a : ctx.alpha) ASSERT_EQ(a, 0.0f) << z;
  }
  RenderContext ctx;
  ASSERT_TRUE(
      Render(camera, {OneGaussian(0, 0, 0.25f, std::log(0.05f), 3, sh0)}, RenderSettings(), &ctx)
          .ok());
  EXPECT_GT(ctx.splats.radius[0], 0);
}

TEST(SplatRendererTest, FrontGaussianOccludesTheOneBehind) {
  const Camera camera = AxisCamera(32, 32, 30, 16.5f, 16.5f);  // axis through pixel (16, 16)
  const float red[3] = {2, -2, -2}, blue[3] = {-2, -2, 2};
  const float colour = 2 * kShC0 + 0.5f;
  const size_t centre = 16 * 32 + 16;
  const GaussianSet front = OneGaussian(0, 0, 2, std::log(0.2f), 6, red);
  for (float back_logit : {1.0f, 6.0f}) {
    const GaussianSet back = OneGaussian(0, 0, 3, std::log(0.3f), back_logit, blue);
    for (int order = 0; order < 2; ++order) {
      RenderContext ctx;
      std::vector<GaussianSet> sets = {front, back};
      if (order) std::swap(sets[0], sets[1]);
      ASSERT_TRUE(Render(camera, sets, RenderSettings(), &ctx).ok());
      // The front Gaussian's alpha is clamped to 0.99 at its centre: 99% red.
      EXPECT_NEAR(ctx.color[3 * centre], 0.99f * colour, 1e-5f);
      if (back_logit == 1.0f) {
        // Behind it, the blue one gets 1% of the pixel, times its own alpha.
        const float blue_alpha = 1 / (1 + std::exp(-back_logit));
        EXPECT_NEAR(ctx.color[3 * centre + 2], 0.01f * blue_alpha * colour, 1e-5f);
      } else {
        // 0.01 * (1 - 0.99) is below the 1e-4 transmittance stop: blue is not blended.
        EXPECT_EQ(ctx.color[3 * centre + 2], 0.0f);
        EXPECT_NEAR(ctx.alpha[centre], 0.99f, 1e-6f);
        EXPECT_EQ(ctx.last_contributor[centre], 1u);
      }
    }
  }
}

TEST(SplatRendererTest, ResultDoesNotDependOnThreadsOrContextReuse) {
  const Camera camera = test::TestCamera(100, 75);
  test::SceneOptions o;
  o.count = 2000;
  std::vector<GaussianSet> sets = {test::RandomGaussians(o, 5)};
  o.count = 300;
  o.sh_degree = 1;
  sets.push_back(test::RandomGaussians(o, 6));
  std::vector<float> error(100 * 75);
  for (size_t p = 0; p < error.size(); ++p) error[p] = static_cast<float>(p % 7) * 0.1f;
  RenderSettings settings;
  settings.blend_weights = true;
  settings.threads = 1;
  RenderContext single;
  ASSERT_TRUE(Render(camera, sets, settings, &single, error.data()).ok());
  RenderContext reused;
  // A different, larger render first, so that buffers are reused.
  ASSERT_TRUE(Render(test::TestCamera(130, 90), {sets[1]}, settings, &reused).ok());
  for (int threads : {2, 3, 0}) {
    settings.threads = threads;
    ASSERT_TRUE(Render(camera, sets, settings, &reused, error.data()).ok());
    EXPECT_EQ(reused.color, single.color) << threads;
    EXPECT_EQ(reused.alpha, single.alpha);
    EXPECT_EQ(reused.blend_weight, single.blend_weight);
    EXPECT_EQ(reused.error_weight, single.error_weight);
    EXPECT_EQ(reused.last_contributor, single.last_contributor);
  }
}

// The tiled float renderer against the brute-force double one on random scenes: two layers
// of different SH degrees, an off-centre principal point, Gaussians across tile borders.
TEST(SplatRendererTest, MatchesBruteForceReference) {
  struct Case {
    int width, height, degree0, degree1, active;
    size_t count;
  };
  const Case cases[] = {
      {48, 40, 3, 1, 3, 30}, {24, 20, 0, 2, 2, 10}, {40, 33, 2, 3, 1, 60}, {64, 48, 3, 3, 3, 200}};
  unsigned seed = 100;
  for (const Case& k : cases) {
    const Camera camera = test::TestCamera(k.width, k.height);
    test::SceneOptions o;
    o.count = k.count;
    o.sh_degree = k.degree0;
    const std::vector<GaussianSet> sets = {test::RandomGaussians(o, seed++), [&] {
                                             o.sh_degree = k.degree1;
                                             o.count = k.count / 2;
                                             return test::RandomGaussians(o, seed++);
                                           }()};
    RenderSettings settings;
    settings.sh_degree = k.active;
    settings.background[1] = 0.5f;
    RenderContext ctx;
    ASSERT_TRUE(Render(camera, sets, settings, &ctx).ok());

    test::RefScene scene;
    for (const GaussianSet& s : sets) scene.layers.push_back(test::ToRefLayer(GaussianView(s)));
    test::RefDecisions decisions;
    const test::ReferenceRenderer ref(camera, k.active, settings.background);
    const test::RefImage expected = ref.Record(scene, &decisions);
    double max_error = 0;
    for (size_t i = 0; i < expected.color.size(); ++i) {
      max_error = std::max(max_error, std::fabs(expected.color[i] - ctx.color[i]));
    }
    for (size_t i = 0; i < expected.alpha.size(); ++i) {
      max_error = std::max(max_error, std::fabs(expected.alpha[i] - ctx.alpha[i]));
    }
    EXPECT_LT(max_error, 2e-5) << k.width << "x" << k.height;
    size_t blends = 0;
    for (const auto& list : decisions.blended) blends += list.size();
    EXPECT_GT(blends, expected.alpha.size()) << "scene too sparse to test anything";
  }
}

TEST(SplatRendererTest, BlendWeightsSumToTheAlphaImageAndMatchDirectSums) {
  const Camera camera = test::TestCamera(56, 44);
  test::SceneOptions o;
  o.count = 80;
  const std::vector<GaussianSet> sets = {test::RandomGaussians(o, 21)};
  std::vector<float> error(56 * 44);
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> e(0.0f, 1.0f);
  for (float& v : error) v = e(rng);
  RenderSettings settings;
  settings.blend_weights = true;
  RenderContext ctx;
  ASSERT_TRUE(Render(camera, sets, settings, &ctx, error.data()).ok());

  double weight_sum = 0, alpha_sum = 0;
  for (float w : ctx.blend_weight) weight_sum += w;
  for (float a : ctx.alpha) alpha_sum += a;
  EXPECT_NEAR(weight_sum, alpha_sum, 1e-5 * alpha_sum);

  // Direct sums over the reference renderer's blend lists.
  test::RefScene scene;
  scene.layers.push_back(test::ToRefLayer(GaussianView(sets[0])));
  test::RefDecisions d;
  const test::ReferenceRenderer ref(camera, 3, settings.background);
  ref.Record(scene, &d);
  const std::vector<test::RefSplat> splats = ref.Project(scene, &d, false);
  std::vector<double> weight(sets[0].size(), 0.0), weighted_error(sets[0].size(), 0.0);
  for (size_t p = 0; p < d.blended.size(); ++p) {
    const double px = p % camera.width + 0.5, py = p / camera.width + 0.5;
    double t = 1;
    for (const auto& [g, clamped] : d.blended[p]) {
      const test::RefSplat& s = splats[g];
      const double dx = s.u - px, dy = s.v - py;
      const double power =
          -0.5 * (s.conic[0] * dx * dx + s.conic[2] * dy * dy) - s.conic[1] * dx * dy;
      const double alpha = clamped ? 0.99 : s.opacity * std::exp(power);
      weight[g] += alpha * t;
      weighted_error[g] += alpha * t * error[p];
      t *= 1 - alpha;
    }
  }
  int nonzero = 0;
  for (size_t g = 0; g < weight.size(); ++g) {
    EXPECT_NEAR(ctx.blend_weight[g], weight[g], 1e-5 * (1 + weight[g])) << g;
    EXPECT_NEAR(ctx.error_weight[g], weighted_error[g], 1e-5 * (1 + weighted_error[g])) << g;
    nonzero += weight[g] > 0.1;
  }
  EXPECT_GT(nonzero, 20);
}

TEST(SplatRendererTest, PolynomialExpIsAccurateAndVectorisesBitExactly) {
  double max_rel = 0;
  float x = -87.0f;
  for (int i = 0; x <= 0.0f; ++i, x = -87.0f + 87.0f * static_cast<float>(i) / 1000000) {
    const float e = ExpNonPositive(x);
    max_rel = std::max(max_rel, std::fabs(e - std::exp(double{x})) / std::exp(double{x}));
  }
  EXPECT_LT(max_rel, 2e-7);
  EXPECT_EQ(ExpNonPositive(0.0f), 1.0f);
  const Lanes v = {-0.0f, -1e-8f, -0.3466f, -0.3467f, -1.0f, -10.5f, -86.9f, -200.0f};
  const Lanes ev = ExpNonPositive(v);
  for (int l = 0; l < kLanes; ++l) EXPECT_EQ(ev[l], ExpNonPositive(v[l])) << l;
}

TEST(SplatRendererTest, NonFiniteGaussiansAreCulled) {
  const Camera camera = test::TestCamera(32, 24);
  test::SceneOptions o;
  o.count = 8;
  o.sh_degree = 1;
  GaussianSet set = test::RandomGaussians(o, 9);
  set.positions[0] = kNaN;
  set.log_scales[3 * 1 + 2] = kNaN;
  set.log_scales[3 * 2] = 200.0f;  // infinite scale
  for (int c = 0; c < 4; ++c) set.rotations[4 * 3 + c] = 0.0f;
  set.opacity_logits[4] = kNaN;
  set.sh[12 * 5 + 4] = kNaN;
  set.positions[3 * 6 + 1] = std::numeric_limits<float>::infinity();
  RenderContext ctx;
  ASSERT_TRUE(Render(camera, {set}, RenderSettings(), &ctx).ok());
  for (size_t i = 0; i < 7; ++i) EXPECT_EQ(ctx.splats.radius[i], 0.0f) << i;
  EXPECT_GT(ctx.splats.radius[7], 0.0f);
  for (float v : ctx.color) ASSERT_TRUE(std::isfinite(v));
}

TEST(SplatRendererTest, BadInputIsRejected) {
  const GaussianSet set = test::RandomGaussians(test::SceneOptions(), 1);
  const M4dGaussians view = GaussianView(set);
  const Camera good = test::TestCamera(32, 24);
  RenderContext ctx;
  const RenderSettings settings;
  ASSERT_TRUE(RenderForward(good, &view, 1, settings, nullptr, &ctx).ok());
  EXPECT_TRUE(ctx.valid);

  auto code = [&](const Camera& c, const M4dGaussians* v, int n, const RenderSettings& s) {
    return RenderForward(c, v, n, s, nullptr, &ctx).code();
  };
  EXPECT_EQ(RenderForward(good, &view, 1, settings, nullptr, nullptr).code(), M4D_ERR_INVALID_ARG);
  Camera c = good;
  for (int w : {0, -5, kMaxImageSide + 1}) {
    c.width = w;
    EXPECT_EQ(code(c, &view, 1, settings), M4D_ERR_INVALID_ARG) << w;
    EXPECT_FALSE(ctx.valid);
  }
  c = good;
  c.width = c.height = 10000;  // each side allowed, the pixel count is not
  EXPECT_EQ(code(c, &view, 1, settings), M4D_ERR_INVALID_ARG);
  c = good;
  c.fx = kNaN;
  EXPECT_EQ(code(c, &view, 1, settings), M4D_ERR_INVALID_ARG);
  c = good;
  c.fy = -1;
  EXPECT_EQ(code(c, &view, 1, settings), M4D_ERR_INVALID_ARG);
  c = good;
  c.rotation[0] = 2;  // not a rotation
  EXPECT_EQ(code(c, &view, 1, settings), M4D_ERR_INVALID_ARG);
  c = good;
  c.translation[1] = kNaN;
  EXPECT_EQ(code(c, &view, 1, settings), M4D_ERR_INVALID_ARG);
  c = good;
  c.near_plane = 0;
  EXPECT_EQ(code(c, &view, 1, settings), M4D_ERR_INVALID_ARG);

  RenderSettings s = settings;
  s.threads = -1;
  EXPECT_EQ(code(good, &view, 1, s), M4D_ERR_INVALID_ARG);
  s = settings;
  s.sh_degree = 4;
  EXPECT_EQ(code(good, &view, 1, s), M4D_ERR_INVALID_ARG);
  s = settings;
  s.background[2] = kNaN;
  EXPECT_EQ(code(good, &view, 1, s), M4D_ERR_INVALID_ARG);

  EXPECT_EQ(code(good, nullptr, 1, settings), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(code(good, &view, -1, settings), M4D_ERR_INVALID_ARG);
  M4dGaussians v = view;
  v.sh = nullptr;
  EXPECT_EQ(code(good, &v, 1, settings), M4D_ERR_INVALID_ARG);
  v = view;
  v.sh_degree = 4;
  EXPECT_EQ(code(good, &v, 1, settings), M4D_ERR_INVALID_ARG);
  v = view;
  v.count = kMaxRenderGaussians + 1;  // rejected before any array is read
  EXPECT_EQ(code(good, &v, 1, settings), M4D_ERR_LIMIT);
  const M4dGaussians two_halves[2] = {[&] {
                                        M4dGaussians h = view;
                                        h.count = kMaxRenderGaussians / 2 + 1;
                                        return h;
                                      }(),
                                      [&] {
                                        M4dGaussians h = view;
                                        h.count = kMaxRenderGaussians / 2;
                                        return h;
                                      }()};
  EXPECT_EQ(code(good, two_halves, 2, settings), M4D_ERR_LIMIT);
  EXPECT_FALSE(ctx.valid);
}

TEST(SplatRendererTest, TooManyTileEntriesFailsBeforeAllocating) {
  // 300 Gaussians each covering all 512 x 512 tiles: 78M pairs, above kMaxTileEntries.
  Camera camera = AxisCamera(8192, 8192, 4000, 4096, 4096);
  test::SceneOptions o;
  o.count = 300;
  o.sh_degree = 0;
  GaussianSet set = test::RandomGaussians(o, 2);
  for (size_t i = 0; i < set.size(); ++i) {
    set.positions[3 * i + 2] = 5.0f;
    for (int a = 0; a < 3; ++a) set.log_scales[3 * i + a] = 1.5f;
  }
  RenderContext ctx;
  RenderSettings settings;
  settings.threads = 1;
  EXPECT_EQ(Render(camera, {set}, settings, &ctx).code(), M4D_ERR_LIMIT);
  EXPECT_TRUE(ctx.color.empty());
  EXPECT_TRUE(ctx.bins.entries.empty());
}

}  // namespace
}  // namespace m4d
