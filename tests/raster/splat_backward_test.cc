// The rasterizer's backward pass (encoder/src/raster) against central finite differences of
// an independent double-precision renderer (tests/raster/reference_splat_renderer.h) that replays
// the forward pass's discrete decisions, so both differentiate the same smooth piece.
//
// Bound: for every parameter group (positions, log scales, rotations, opacity logits, SH,
// 2D means) of every scene,
//   max_k |analytic_k - fd_k| / (|fd_k| + 1e-3 max_k |fd_k|) < 2e-3,
// i.e. 0.2% relative error, with an absolute floor at 0.1% of the group's largest gradient
// for entries near zero (float rounding of sums over hundreds of pixels).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "encoder/src/raster/projection_backward.h"
#include "encoder/src/raster/render_context.h"
#include "encoder/src/raster/splat_backward.h"
#include "encoder/src/raster/splat_renderer.h"
#include "encoder/src/raster/viewspace_gradient.h"
#include "sdk/src/layers/gaussian_set.h"
#include "tests/raster/reference_splat_renderer.h"
#include "tests/raster/splat_test_scenes.h"

namespace m4d {
namespace {

constexpr double kRelativeBound = 2e-3;
constexpr double kFloorFraction = 1e-3;
constexpr double kStep = 1e-5;

struct Loss {
  std::vector<float> dl_dcolor, dl_dalpha;  // the weights of L = w_c . C + w_a . A
};

Loss RandomLoss(const Camera& camera, bool with_alpha, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  Loss loss;
  const size_t pixels = static_cast<size_t>(camera.width) * camera.height;
  loss.dl_dcolor.resize(3 * pixels);
  for (float& v : loss.dl_dcolor) v = u(rng);
  if (with_alpha) {
    loss.dl_dalpha.resize(pixels);
    for (float& v : loss.dl_dalpha) v = u(rng);
  }
  return loss;
}

double Evaluate(const test::RefImage& image, const Loss& loss) {
  double l = 0;
  for (size_t i = 0; i < image.color.size(); ++i) l += loss.dl_dcolor[i] * image.color[i];
  for (size_t i = 0; i < loss.dl_dalpha.size(); ++i) l += loss.dl_dalpha[i] * image.alpha[i];
  return l;
}

// Owns the analytic gradients of a rendered scene.
struct Gradients {
  std::vector<std::vector<float>> positions, log_scales, rotations, logits, sh;
  std::vector<float> mean2d;
  std::vector<LayerGradients> views;
  bool with_mean2d = true;

  explicit Gradients(const std::vector<GaussianSet>& sets) {
    size_t total = 0;
    for (const GaussianSet& s : sets) {
      positions.emplace_back(3 * s.size(), -7.0f);  // garbage: must be overwritten
      log_scales.emplace_back(3 * s.size(), -7.0f);
      rotations.emplace_back(4 * s.size(), -7.0f);
      logits.emplace_back(s.size(), -7.0f);
      sh.emplace_back(s.sh.size(), -7.0f);
      total += s.size();
    }
    mean2d.assign(2 * total, -7.0f);
    for (size_t l = 0; l < sets.size(); ++l) {
      LayerGradients v;
      v.positions = positions[l].data();
      v.log_scales = log_scales[l].data();
      v.rotations = rotations[l].data();
      v.opacity_logits = logits[l].data();
      v.sh = sh[l].data();
      views.push_back(v);
    }
  }

  SplatGradients Outputs() {
    SplatGradients out;
    out.layers = views.data();
    out.layer_count = static_cast<int>(views.size());
    out.mean2d = with_mean2d ? mean2d.data() : nullptr;
    return out;
  }
};

struct Case {
  std::string name;
  int width, height;
  std::vector<test::SceneOptions> layers;
  int active_degree = 3;
  bool with_alpha = false;
  float background[3] = {0, 0, 0};
  unsigned seed = 1;
};

Status RunForwardBackward(const Camera& camera, const std::vector<GaussianSet>& sets,
                          const RenderSettings& settings, const Loss& loss, RenderContext* ctx,
                          Gradients* grads) {
  const std::vector<M4dGaussians> views = test::Views(sets);
  M4D_RETURN_IF_ERROR(
      RenderForward(camera, views.data(), static_cast<int>(views.size()), settings, nullptr, ctx));
  BackwardWorkspace ws;
  return RenderBackward(loss.dl_dcolor.data(),
                        loss.dl_dalpha.empty() ? nullptr : loss.dl_dalpha.data(), ctx,
                        grads->Outputs(), &ws);
}

// Compares one parameter group; returns the worst relative error.
double CompareGroup(const std::string& what, const std::vector<double>& analytic,
                    const std::vector<double>& fd) {
  double largest = 0;
  for (double f : fd) largest = std::max(largest, std::fabs(f));
  double worst = 0;
  size_t worst_k = 0;
  for (size_t k = 0; k < fd.size(); ++k) {
    const double e = std::fabs(analytic[k] - fd[k]) / (std::fabs(fd[k]) + kFloorFraction * largest);
    if (e > worst) {
      worst = e;
      worst_k = k;
    }
  }
  EXPECT_LT(worst, kRelativeBound) << what << ": parameter " << worst_k << " analytic "
                                   << analytic[worst_k] << " fd " << fd[worst_k];
  EXPECT_GT(largest, 0.0) << what << ": no gradient at all";
  return worst;
}

void CheckGradients(const Case& c) {
  SCOPED_TRACE(c.name);
  const Camera camera = test::TestCamera(c.width, c.height);
  std::vector<GaussianSet> sets;
  for (size_t l = 0; l < c.layers.size(); ++l) {
    sets.push_back(test::RandomGaussians(c.layers[l], c.seed * 17 + static_cast<unsigned>(l)));
  }
  RenderSettings settings;
  settings.sh_degree = c.active_degree;
  std::copy(c.background, c.background + 3, settings.background);
  const Loss loss = RandomLoss(camera, c.with_alpha, c.seed);
  RenderContext ctx;
  Gradients grads(sets);
  ASSERT_TRUE(RunForwardBackward(camera, sets, settings, loss, &ctx, &grads).ok());

  test::RefScene scene;
  for (const GaussianSet& s : sets) scene.layers.push_back(test::ToRefLayer(GaussianView(s)));
  scene.mean_offset.assign(2 * scene.size(), 0.0);
  const test::ReferenceRenderer ref(camera, c.active_degree, settings.background);
  test::RefDecisions decisions;
  const double base = Evaluate(ref.Record(scene, &decisions), loss);
  ASSERT_NEAR(Evaluate(ref.Replay(scene, decisions), loss), base, 1e-12 * (1 + std::fabs(base)));
  auto fd = [&](double* param) {
    const double keep = *param;
    *param = keep + kStep;
    const double plus = Evaluate(ref.Replay(scene, decisions), loss);
    *param = keep - kStep;
    const double minus = Evaluate(ref.Replay(scene, decisions), loss);
    *param = keep;
    return (plus - minus) / (2 * kStep);
  };
  auto check = [&](const std::string& what, std::vector<float>* analytic_f,
                   std::vector<double>* params, const std::vector<bool>& active) {
    std::vector<double> analytic, numeric;
    for (size_t k = 0; k < params->size(); ++k) {
      if (!active[k]) {
        EXPECT_EQ((*analytic_f)[k], 0.0f) << what << " " << k << " must be zero";
        continue;
      }
      analytic.push_back((*analytic_f)[k]);
      numeric.push_back(fd(&(*params)[k]));
    }
    CompareGroup(what, analytic, numeric);
  };
  for (size_t l = 0; l < sets.size(); ++l) {
    test::RefLayer& layer = scene.layers[l];
    const std::string name = "layer " + std::to_string(l) + " ";
    check(name + "positions", &grads.positions[l], &layer.positions,
          std::vector<bool>(layer.positions.size(), true));
    check(name + "log_scales", &grads.log_scales[l], &layer.log_scales,
          std::vector<bool>(layer.log_scales.size(), true));
    check(name + "rotations", &grads.rotations[l], &layer.rotations,
          std::vector<bool>(layer.rotations.size(), true));
    check(name + "opacity_logits", &grads.logits[l], &layer.opacity_logits,
          std::vector<bool>(layer.opacity_logits.size(), true));
    // Coefficients beyond the active degree get exactly zero.
    const int stored = ShCoefficients(layer.sh_degree);
    const int active = ShCoefficients(std::min(c.active_degree, layer.sh_degree));
    std::vector<bool> sh_active(layer.sh.size());
    for (size_t k = 0; k < sh_active.size(); ++k) {
      sh_active[k] = static_cast<int>(k / 3 % stored) < active;
    }
    check(name + "sh", &grads.sh[l], &layer.sh, sh_active);
  }
  check("mean2d", &grads.mean2d, &scene.mean_offset,
        std::vector<bool>(scene.mean_offset.size(), true));
}

test::SceneOptions Options(size_t count, int degree) {
  test::SceneOptions o;
  o.count = count;
  o.sh_degree = degree;
  return o;
}

TEST(SplatBackwardTest, GradientsMatchFiniteDifferences) {
  std::vector<Case> cases;
  {
    Case c;
    c.name = "5 Gaussians, SH 0, 24x20";
    c.width = 24;
    c.height = 20;
    c.layers = {Options(5, 0)};
    c.seed = 1;
    cases.push_back(c);
  }
  {
    Case c;
    c.name = "two layers SH 3 + SH 1, 48x40, background";
    c.width = 48;
    c.height = 40;
    c.layers = {Options(20, 3), Options(10, 1)};
    c.background[0] = 0.3f;
    c.background[2] = 0.8f;
    c.seed = 2;
    cases.push_back(c);
  }
  {
    Case c;
    c.name = "SH 2 with active degree 1, dL/dalpha, 40x33";
    c.width = 40;
    c.height = 33;
    c.layers = {Options(30, 2)};
    c.active_degree = 1;
    c.with_alpha = true;
    c.background[1] = 0.5f;
    c.seed = 3;
    cases.push_back(c);
  }
  for (const Case& c : cases) CheckGradients(c);
}

// Opaque, overlapping Gaussians: alphas clamp at 0.99, pixels stop at the transmittance
// threshold, colours clamp at zero. The decisions freeze in the finite differences as in
// the analytic gradient.
TEST(SplatBackwardTest, GradientsMatchWithClampsAndEarlyStops) {
  Case c;
  c.name = "opaque, 36x30";
  c.width = 36;
  c.height = 30;
  test::SceneOptions o = Options(30, 3);
  o.extent = 0.8f;
  o.log_scale_lo = -1.6f;
  o.log_scale_hi = -0.8f;
  o.logit_lo = 5.0f;
  o.logit_hi = 10.0f;
  o.sh_dc = 2.5f;
  c.layers = {o};
  c.with_alpha = true;
  c.seed = 4;

  // The scene must exercise what it claims to.
  const Camera camera = test::TestCamera(c.width, c.height);
  test::RefScene scene;
  const GaussianSet set = test::RandomGaussians(o, c.seed * 17);
  scene.layers.push_back(test::ToRefLayer(GaussianView(set)));
  test::RefDecisions d;
  test::ReferenceRenderer(camera, 3, c.background).Record(scene, &d);
  int clamped_alpha = 0, stopped = 0, clamped_colour = 0;
  for (const auto& list : d.blended) {
    for (const auto& entry : list) clamped_alpha += entry.second;
  }
  for (bool s : d.stopped) stopped += s;
  for (uint8_t f : d.color_clamped) clamped_colour += f != 0;
  EXPECT_GT(clamped_alpha, 10);
  EXPECT_GT(stopped, 10);
  EXPECT_GT(clamped_colour, 2);
  CheckGradients(c);
}

// Gaussians beside the view, large enough to reach into it: X/Z is clamped in the Jacobian.
TEST(SplatBackwardTest, GradientsMatchWithClampedJacobian) {
  Case c;
  c.name = "beside the frustum, 32x24";
  c.width = 32;
  c.height = 24;
  test::SceneOptions o = Options(12, 1);
  o.extent = 3.5f;
  o.log_scale_lo = -0.6f;
  o.log_scale_hi = 0.0f;
  o.logit_lo = -2.0f;
  o.logit_hi = -0.5f;
  c.layers = {o};
  c.seed = 5;

  const Camera camera = test::TestCamera(c.width, c.height);
  test::RefScene scene;
  scene.layers.push_back(test::ToRefLayer(GaussianView(test::RandomGaussians(o, c.seed * 17))));
  test::RefDecisions d;
  test::ReferenceRenderer(camera, 3, c.background).Record(scene, &d);
  int clamped_visible = 0;
  for (size_t g = 0; g < d.visible.size(); ++g) {
    clamped_visible += d.visible[g] && d.jacobian_clamped[g] != 0;
  }
  EXPECT_GE(clamped_visible, 2);
  CheckGradients(c);
}

TEST(SplatBackwardTest, ViewspaceNormIsTheGradientInNdcUnits) {
  // Finite differences in NDC units: an NDC shift of delta moves the mean by delta * size / 2
  // pixels.
  const Camera camera = test::TestCamera(40, 30);
  const std::vector<GaussianSet> sets = {test::RandomGaussians(Options(10, 1), 31)};
  const Loss loss = RandomLoss(camera, false, 8);
  RenderContext ctx;
  Gradients grads(sets);
  ASSERT_TRUE(RunForwardBackward(camera, sets, RenderSettings(), loss, &ctx, &grads).ok());
  test::RefScene scene;
  scene.layers.push_back(test::ToRefLayer(GaussianView(sets[0])));
  scene.mean_offset.assign(2 * scene.size(), 0.0);
  const float bg[3] = {0, 0, 0};
  const test::ReferenceRenderer ref(camera, 3, bg);
  test::RefDecisions d;
  ref.Record(scene, &d);
  int checked = 0;
  for (size_t g = 0; g < scene.size(); ++g) {
    double ndc_grad[2];
    for (int a = 0; a < 2; ++a) {
      const double pixels_per_ndc = 0.5 * (a == 0 ? camera.width : camera.height);
      scene.mean_offset[2 * g + a] = kStep * pixels_per_ndc;
      const double plus = Evaluate(ref.Replay(scene, d), loss);
      scene.mean_offset[2 * g + a] = -kStep * pixels_per_ndc;
      const double minus = Evaluate(ref.Replay(scene, d), loss);
      scene.mean_offset[2 * g + a] = 0;
      ndc_grad[a] = (plus - minus) / (2 * kStep);
    }
    const double expected = std::hypot(ndc_grad[0], ndc_grad[1]);
    if (expected < 1e-3) continue;
    EXPECT_NEAR(ViewspaceGradientNorm(&grads.mean2d[2 * g], camera.width, camera.height), expected,
                1e-2 * expected);
    ++checked;
  }
  EXPECT_GT(checked, 5);
}

// The backward pass replays each pixel's forward walk and fails if it does not end with the
// forward pass's exact final transmittance and last contributor: on dense scenes any
// difference in the alpha arithmetic (e.g. contraction into FMA) would show.
TEST(SplatBackwardTest, ReplayReproducesTheForwardPassBitForBit) {
  for (int k = 0; k < 3; ++k) {
    const Camera camera = test::TestCamera(64 + 37 * k, 48 + 21 * k);
    test::SceneOptions o = Options(1500 * (k + 1), k);
    o.logit_lo = -2.0f;
    o.logit_hi = 6.0f;
    const std::vector<GaussianSet> sets = {test::RandomGaussians(o, 50 + k)};
    RenderContext ctx;
    Gradients grads(sets);
    const Status status = RunForwardBackward(camera, sets, RenderSettings(),
                                             RandomLoss(camera, true, k), &ctx, &grads);
    EXPECT_TRUE(status.ok()) << status.message();
    size_t stopped = 0;
    for (float t : ctx.final_transmittance) stopped += t < 1e-3f;
    EXPECT_GT(stopped, ctx.final_transmittance.size() / 4) << "scene not dense enough";
  }
}

TEST(SplatBackwardTest, GradientsDoNotDependOnThreads) {
  const Camera camera = test::TestCamera(120, 90);
  test::SceneOptions o = Options(3000, 3);
  const std::vector<GaussianSet> sets = {test::RandomGaussians(o, 41)};
  const Loss loss = RandomLoss(camera, true, 9);
  RenderSettings settings;
  settings.threads = 1;
  RenderContext single_ctx;
  Gradients single(sets);
  ASSERT_TRUE(RunForwardBackward(camera, sets, settings, loss, &single_ctx, &single).ok());
  for (int threads : {2, 3}) {
    settings.threads = threads;
    RenderContext ctx;
    Gradients multi(sets);
    ASSERT_TRUE(RunForwardBackward(camera, sets, settings, loss, &ctx, &multi).ok());
    EXPECT_EQ(multi.positions, single.positions) << threads;
    EXPECT_EQ(multi.log_scales, single.log_scales);
    EXPECT_EQ(multi.rotations, single.rotations);
    EXPECT_EQ(multi.logits, single.logits);
    EXPECT_EQ(multi.sh, single.sh);
    EXPECT_EQ(multi.mean2d, single.mean2d);
  }
}

TEST(SplatBackwardTest, FrozenLayerGetsNothingAndTheOtherLayerIsUnchanged) {
  const Camera camera = test::TestCamera(120, 90);
  const std::vector<GaussianSet> sets = {test::RandomGaussians(Options(800, 3), 51),
                                         test::RandomGaussians(Options(600, 1), 52)};
  const Loss loss = RandomLoss(camera, false, 10);
  RenderSettings settings;
  RenderContext ctx;
  Gradients all(sets);
  ASSERT_TRUE(RunForwardBackward(camera, sets, settings, loss, &ctx, &all).ok());
  Gradients frozen(sets);
  frozen.views[0] = LayerGradients();  // layer 0 frozen: all arrays null
  ASSERT_TRUE(RunForwardBackward(camera, sets, settings, loss, &ctx, &frozen).ok());
  EXPECT_EQ(frozen.positions[1], all.positions[1]);
  EXPECT_EQ(frozen.rotations[1], all.rotations[1]);
  EXPECT_EQ(frozen.sh[1], all.sh[1]);
  EXPECT_EQ(frozen.mean2d, all.mean2d);  // the view-space gradient covers frozen layers too
  EXPECT_EQ(frozen.positions[0], std::vector<float>(3 * sets[0].size(), -7.0f));
  // Some but not all arrays null is an error.
  Gradients partial(sets);
  partial.views[0].sh = nullptr;
  EXPECT_EQ(RunForwardBackward(camera, sets, settings, loss, &ctx, &partial).code(),
            M4D_ERR_INVALID_ARG);
}

// Two layers: 900 Gaussians spread over the view, and 60 within 0.25 of the scene's centre.
std::vector<GaussianSet> WideAndSmallLayers(unsigned seed) {
  test::SceneOptions small = Options(60, 1);
  small.extent = 0.25f;
  return {test::RandomGaussians(Options(900, 1), seed), test::RandomGaussians(small, seed + 1)};
}

// Without view-space gradients a frozen leading layer needs none: its tiles and pixel groups
// without a trained splat are skipped, and the trained layer's gradients stay bit for bit.
TEST(SplatBackwardTest, FrozenLeadingLayerIsSkippedAndTheOtherLayerIsUnchanged) {
  const Camera camera = test::TestCamera(160, 120);
  const std::vector<GaussianSet> sets = WideAndSmallLayers(61);
  const Loss loss = RandomLoss(camera, true, 11);
  RenderSettings settings;
  RenderContext ctx;
  Gradients all(sets);
  all.with_mean2d = false;
  ASSERT_TRUE(RunForwardBackward(camera, sets, settings, loss, &ctx, &all).ok());
  Gradients frozen(sets);
  frozen.with_mean2d = false;
  frozen.views[0] = LayerGradients();
  ASSERT_TRUE(RunForwardBackward(camera, sets, settings, loss, &ctx, &frozen).ok());
  EXPECT_EQ(frozen.positions[1], all.positions[1]);
  EXPECT_EQ(frozen.log_scales[1], all.log_scales[1]);
  EXPECT_EQ(frozen.rotations[1], all.rotations[1]);
  EXPECT_EQ(frozen.logits[1], all.logits[1]);
  EXPECT_EQ(frozen.sh[1], all.sh[1]);
  EXPECT_NE(all.positions[1], std::vector<float>(3 * sets[1].size(), 0.0f));
}

// After a focused pass (only the tiles the second layer reaches rendered), view-space
// gradients cover the focus layer, bit for bit those of the whole render, and are zero for the
// layer before it, whose other tiles were never blended.
TEST(SplatBackwardTest, FocusedPassGivesViewspaceGradientsOfTheFocusLayers) {
  const Camera camera = test::TestCamera(160, 120);
  const std::vector<GaussianSet> sets = WideAndSmallLayers(63);
  const Loss loss = RandomLoss(camera, false, 12);
  RenderSettings settings;
  RenderContext ctx;
  Gradients all(sets);
  all.views[0] = LayerGradients();
  ASSERT_TRUE(RunForwardBackward(camera, sets, settings, loss, &ctx, &all).ok());
  RenderSettings focused = settings;
  focused.focus_layer = 1;
  focused.focus_margin = 0;
  Gradients focus(sets);
  focus.views[0] = LayerGradients();
  ASSERT_TRUE(RunForwardBackward(camera, sets, focused, loss, &ctx, &focus).ok());
  const size_t first = 2 * sets[0].size();
  EXPECT_TRUE(
      std::equal(focus.mean2d.begin() + first, focus.mean2d.end(), all.mean2d.begin() + first));
  EXPECT_EQ(focus.positions[1], all.positions[1]);
  EXPECT_TRUE(std::all_of(focus.mean2d.begin(), focus.mean2d.begin() + first,
                          [](float g) { return g == 0.0f; }));
  EXPECT_TRUE(std::any_of(all.mean2d.begin(), all.mean2d.begin() + first,
                          [](float g) { return g != 0.0f; }));
}

TEST(SplatBackwardTest, CulledGaussiansGetZeroGradients) {
  const Camera camera = test::TestCamera(32, 24);
  GaussianSet set = test::RandomGaussians(Options(6, 2), 12);
  set.positions[3 * 2 + 2] = -20.0f;  // behind the camera
  const std::vector<GaussianSet> sets = {set};
  RenderContext ctx;
  Gradients grads(sets);
  ASSERT_TRUE(
      RunForwardBackward(camera, sets, RenderSettings(), RandomLoss(camera, true, 3), &ctx, &grads)
          .ok());
  ASSERT_EQ(ctx.splats.radius[2], 0.0f);
  for (int a = 0; a < 3; ++a) EXPECT_EQ(grads.positions[0][6 + a], 0.0f);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(grads.rotations[0][8 + k], 0.0f);
  EXPECT_EQ(grads.logits[0][2], 0.0f);
  for (int k = 0; k < 27; ++k) EXPECT_EQ(grads.sh[0][27 * 2 + k], 0.0f);
  EXPECT_EQ(grads.mean2d[4], 0.0f);
  EXPECT_NE(grads.logits[0][0], 0.0f);
}

TEST(SplatBackwardTest, BadInputIsRejected) {
  const Camera camera = test::TestCamera(32, 24);
  const std::vector<GaussianSet> sets = {test::RandomGaussians(Options(10, 1), 13)};
  const Loss loss = RandomLoss(camera, false, 4);
  RenderContext ctx;
  Gradients grads(sets);
  BackwardWorkspace ws;
  // No forward pass yet.
  EXPECT_EQ(RenderBackward(loss.dl_dcolor.data(), nullptr, &ctx, grads.Outputs(), &ws).code(),
            M4D_ERR_INVALID_ARG);
  ASSERT_TRUE(RunForwardBackward(camera, sets, RenderSettings(), loss, &ctx, &grads).ok());
  EXPECT_TRUE(RenderBackward(loss.dl_dcolor.data(), nullptr, &ctx, grads.Outputs(), &ws).ok());
  EXPECT_EQ(RenderBackward(nullptr, nullptr, &ctx, grads.Outputs(), &ws).code(),
            M4D_ERR_INVALID_ARG);
  EXPECT_EQ(RenderBackward(loss.dl_dcolor.data(), nullptr, nullptr, grads.Outputs(), &ws).code(),
            M4D_ERR_INVALID_ARG);
  EXPECT_EQ(RenderBackward(loss.dl_dcolor.data(), nullptr, &ctx, grads.Outputs(), nullptr).code(),
            M4D_ERR_INVALID_ARG);
  SplatGradients out = grads.Outputs();
  out.layer_count = 2;
  EXPECT_EQ(RenderBackward(loss.dl_dcolor.data(), nullptr, &ctx, out, &ws).code(),
            M4D_ERR_INVALID_ARG);
  grads.views[0].sh = nullptr;
  EXPECT_EQ(RenderBackward(loss.dl_dcolor.data(), nullptr, &ctx, grads.Outputs(), &ws).code(),
            M4D_ERR_INVALID_ARG);
  grads.views[0].sh = grads.sh[0].data();

  // A modified forward state is detected by the replay.
  size_t covered = 0;
  while (ctx.last_contributor[covered] == 0) ++covered;
  ctx.final_transmittance[covered] *= 0.5f;
  EXPECT_EQ(RenderBackward(loss.dl_dcolor.data(), nullptr, &ctx, grads.Outputs(), &ws).code(),
            M4D_ERR_INVALID_ARG);
  // A failed forward pass leaves nothing to differentiate.
  Camera bad = camera;
  bad.width = 0;
  const std::vector<M4dGaussians> views = test::Views(sets);
  EXPECT_FALSE(RenderForward(bad, views.data(), 1, RenderSettings(), nullptr, &ctx).ok());
  EXPECT_EQ(RenderBackward(loss.dl_dcolor.data(), nullptr, &ctx, grads.Outputs(), &ws).code(),
            M4D_ERR_INVALID_ARG);
}

}  // namespace
}  // namespace m4d
