// Gaussian compensation (paper 3.4, 4.3): candidates optimised over a fixed scene, the
// sparsity term removing Gaussians, unseen Gaussians removed.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "encoder/src/compensation/compensation_candidates.h"
#include "encoder/src/compensation/compensation_training.h"
#include "encoder/src/metrics/photometric_loss.h"
#include "encoder/src/metrics/psnr.h"
#include "encoder/src/raster/splat_backward.h"
#include "encoder/src/raster/splat_renderer.h"
#include "encoder/src/raster/viewspace_gradient.h"
#include "encoder/src/train/training_views.h"
#include "tests/raster/splat_test_scenes.h"

namespace m4d {
namespace {

constexpr int kWidth = 64, kHeight = 48, kCameras = 6;

struct Scene {
  GaussianSet static_set, moved;
  TrainingViews views;
};

// The truth: the moved blob with a brighter colour on its upper half, which the moved set
// (the prediction) lacks. The moved set also has one Gaussian behind every camera.
Scene MakeScene() {
  Scene s;
  test::SceneOptions background;
  background.count = 300;
  background.sh_degree = 0;
  background.extent = 1.5f;
  s.static_set = test::RandomGaussians(background, 31);
  for (size_t i = 0; i < s.static_set.size(); ++i) s.static_set.positions[3 * i + 2] += 1.5f;
  test::SceneOptions blob;
  blob.count = 120;
  blob.sh_degree = 0;
  blob.extent = 0.4f;
  blob.logit_lo = 1.0f;
  blob.logit_hi = 3.0f;
  GaussianSet truth = test::RandomGaussians(blob, 32);
  s.moved = truth;
  for (size_t i = 0; i < truth.size(); ++i) {
    if (truth.positions[3 * i + 1] < 0) truth.sh[3 * i] += 1.5f;
  }
  s.moved.Resize(truth.size() + 1);
  const size_t last = truth.size();
  s.moved.positions[3 * last + 2] = -20.0f;  // behind the cameras
  s.moved.rotations[4 * last] = 1.0f;
  const M4dGaussians layers[2] = {GaussianView(s.static_set), GaussianView(truth)};
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

double MeanPsnr(const Scene& s, const GaussianSet& moved, const std::vector<uint8_t>& removed,
                const GaussianSet& added) {
  GaussianSet kept = moved;
  kept.Resize(0);
  for (size_t i = 0; i < moved.size(); ++i) {
    if (removed[i]) continue;
    size_t j = kept.size();
    kept.Resize(j + 1);
    std::copy_n(&moved.positions[3 * i], 3, &kept.positions[3 * j]);
    std::copy_n(&moved.log_scales[3 * i], 3, &kept.log_scales[3 * j]);
    std::copy_n(&moved.rotations[4 * i], 4, &kept.rotations[4 * j]);
    kept.opacity_logits[j] = moved.opacity_logits[i];
    std::copy_n(&moved.sh[3 * i], 3, &kept.sh[3 * j]);
  }
  const M4dGaussians layers[3] = {GaussianView(s.static_set), GaussianView(kept),
                                  GaussianView(added)};
  RenderSettings settings;
  RenderContext context;
  double sum = 0;
  for (int v = 0; v < s.views.size(); ++v) {
    EXPECT_TRUE(RenderForward(s.views.cameras[v], layers, 3, settings, nullptr, &context).ok());
    Image image(kWidth, kHeight, 3);
    for (size_t i = 0; i < image.pixels.size(); ++i) {
      image.pixels[i] = std::clamp(context.color[i], 0.0f, 1.0f);
    }
    double psnr = 0;
    EXPECT_TRUE(Psnr(image, s.views.images[v], &psnr).ok());
    sum += psnr;
  }
  return sum / s.views.size();
}

CompensationCandidates Candidates(const Scene& s, float threshold) {
  std::vector<float> gradient;
  EXPECT_TRUE(
      MeasureViewspaceGradients(s.views, s.static_set, s.moved, 0, EncodeContext(), &gradient)
          .ok());
  std::vector<float> motion(7 * s.moved.size(), 0.0f);
  CompensationThresholds t;
  t.gradient = threshold;
  return ProposeCompensation(s.moved, gradient, motion, t, 1);
}

TEST(CompensationTrainingTest, ImprovesTheFrameAndRemovesUnseenGaussians) {
  Scene s = MakeScene();
  CompensationCandidates candidates = Candidates(s, 0.0f);  // replicate every visible one
  ASSERT_GT(candidates.added.size(), 50u);
  CompensationOptions options;
  options.iterations = 300;
  options.sh_degree = 0;
  options.sparsity_weight = 1e-6;
  CompensationResult result;
  ASSERT_TRUE(TrainCompensation(s.views, s.static_set, s.moved, candidates, options, &result).ok());
  EXPECT_EQ(result.removed.back(), 1);
  EXPECT_GE(result.removed_unseen, 1u);  // and any blob Gaussian hidden from every view
  GaussianSet none;
  const double before = MeanPsnr(s, s.moved, std::vector<uint8_t>(s.moved.size(), 0), none);
  const double after = MeanPsnr(s, s.moved, result.removed, result.added);
  EXPECT_GT(after, before + 3.0) << before << " -> " << after;
}

TEST(CompensationTrainingTest, SparsityWeightRemovesGaussians) {
  Scene s = MakeScene();
  CompensationCandidates candidates = Candidates(s, 0.0f);
  auto kept = [&](double weight) {
    CompensationOptions options;
    options.iterations = 150;
    options.sh_degree = 0;
    options.sparsity_weight = weight;
    CompensationResult result;
    EXPECT_TRUE(
        TrainCompensation(s.views, s.static_set, s.moved, candidates, options, &result).ok());
    EXPECT_EQ(result.added.size() + result.pruned_added, candidates.added.size());
    return result.added.size();
  };
  const size_t light = kept(0.0), heavy = kept(1e-2);
  EXPECT_LT(heavy, light / 2) << light << " vs " << heavy;
}

size_t RemovedCount(const CompensationResult& result) {
  return static_cast<size_t>(std::count(result.removed.begin(), result.removed.end(), 1));
}

// The early decision: the probe measures the Gaussians trained so far, halfway to the probe
// iteration and at it, without disturbing the training. Where compensation serves (the blob's
// missing colour) its gain is on course for the threshold and the training goes on; under a
// threshold out of its reach it ends at the probe iteration, adding and removing nothing.
TEST(CompensationTrainingTest, EarlyDecisionEndsOnlyTheTrainingThatWouldNotPay) {
  Scene s = MakeScene();
  CompensationCandidates candidates = Candidates(s, 0.0f);
  CompensationOptions options;
  options.iterations = 60;
  options.probe_iteration = 20;
  options.sh_degree = 0;
  CompensationResult plain;
  ASSERT_TRUE(TrainCompensation(s.views, s.static_set, s.moved, candidates, options, &plain).ok());
  const double before = MeanPsnr(s, s.moved, std::vector<uint8_t>(s.moved.size(), 0), {});
  const double after = MeanPsnr(s, s.moved, plain.removed, plain.added);
  std::vector<double> gains;
  auto measure = [&](const GaussianSet& kept, const GaussianSet& added, double* gain) {
    EXPECT_EQ(kept.size(), s.moved.size() - RemovedCount(plain));
    EXPECT_GT(added.size(), 0u);
    *gain = MeanPsnr(s, kept, std::vector<uint8_t>(kept.size(), 0), added) - before;
    gains.push_back(*gain);
    return Status::Ok();
  };

  options.probe_min_gain = after - before;  // reached at the last iteration
  CompensationResult probed;
  CompensationSharing sharing;
  sharing.probe = measure;
  ASSERT_TRUE(
      TrainCompensation(s.views, s.static_set, s.moved, candidates, options, &probed, sharing)
          .ok());
  ASSERT_EQ(gains.size(), 2u);
  EXPECT_LT(gains[0], gains[1]);
  EXPECT_LT(gains[1], after - before);
  EXPECT_FALSE(probed.abandoned);
  EXPECT_EQ(probed.probed_gain, gains[1]);
  EXPECT_EQ(probed.removed, plain.removed);
  EXPECT_EQ(probed.added.positions, plain.added.positions);
  EXPECT_EQ(probed.added.sh, plain.added.sh);

  // Twice what the line from the two probes reaches at the last iteration.
  options.probe_min_gain = 2 * (gains[1] + (gains[1] - gains[0]) * 40 / 10);
  gains.clear();
  CompensationResult ended;
  ASSERT_TRUE(
      TrainCompensation(s.views, s.static_set, s.moved, candidates, options, &ended, sharing).ok());
  ASSERT_EQ(gains.size(), 2u);
  EXPECT_TRUE(ended.abandoned);
  EXPECT_EQ(ended.probed_gain, gains[1]);
  EXPECT_EQ(ended.added.size(), 0u);
  EXPECT_EQ(RemovedCount(ended), 0u);
  EXPECT_EQ(ended.pruned_added, candidates.added.size());
}

// The viewspace measure's renders give the blend weights that decide which moved Gaussians no
// view sees: shared with the training, it removes the same ones and trains the same result.
TEST(CompensationTrainingTest, SharedBlendWeightsRemoveTheSameGaussians) {
  Scene s = MakeScene();
  std::vector<float> gradient, weight;
  ASSERT_TRUE(MeasureViewspaceGradients(s.views, s.static_set, s.moved, 0, EncodeContext(),
                                        &gradient, nullptr, &weight)
                  .ok());
  ASSERT_EQ(weight.size(), s.moved.size());
  EXPECT_EQ(weight.back(), 0.0f);  // behind every camera
  EXPECT_GT(*std::max_element(weight.begin(), weight.end()), 1.0f);
  CompensationCandidates candidates = Candidates(s, 0.0f);
  CompensationOptions options;
  options.iterations = 30;
  options.sh_degree = 0;
  CompensationResult own, shared;
  ASSERT_TRUE(TrainCompensation(s.views, s.static_set, s.moved, candidates, options, &own).ok());
  CompensationSharing sharing;
  sharing.moved_blend_weight = &weight;
  ASSERT_TRUE(
      TrainCompensation(s.views, s.static_set, s.moved, candidates, options, &shared, sharing)
          .ok());
  EXPECT_GE(own.removed_unseen, 1u);
  EXPECT_EQ(shared.removed_unseen, own.removed_unseen);
  EXPECT_EQ(shared.removed, own.removed);
  EXPECT_EQ(shared.added.positions, own.added.positions);
  weight.pop_back();
  EXPECT_FALSE(
      TrainCompensation(s.views, s.static_set, s.moved, candidates, options, &shared, sharing)
          .ok());
}

// The measure renders only the tiles the moved set reaches and reads the rest from the static
// layer's render: each moved Gaussian gets what a pass over the whole image gives it.
TEST(CompensationTrainingTest, ViewspaceGradientsAreTheWholeImagesMean) {
  Scene s = MakeScene();
  std::vector<float> measured;
  ASSERT_TRUE(
      MeasureViewspaceGradients(s.views, s.static_set, s.moved, 0, EncodeContext(), &measured)
          .ok());
  const M4dGaussians layers[2] = {GaussianView(s.static_set), GaussianView(s.moved)};
  const size_t offset = s.static_set.size(), n = s.moved.size();
  std::vector<float> mean2d(2 * (offset + n)), sum(n, 0.0f);
  std::vector<int> seen(n, 0);
  LayerGradients frozen[2];
  SplatGradients outputs;
  outputs.layers = frozen;
  outputs.layer_count = 2;
  outputs.mean2d = mean2d.data();
  RenderSettings settings;
  settings.sh_degree = 0;
  RenderContext context;
  BackwardWorkspace workspace;
  PhotometricLoss loss;
  Image grad;
  for (int v = 0; v < s.views.size(); ++v) {
    const Camera& camera = s.views.cameras[v];
    ASSERT_TRUE(RenderForward(camera, layers, 2, settings, nullptr, &context).ok());
    Image rendered(kWidth, kHeight, 3);
    rendered.pixels = context.color;
    PhotometricLossValue value;
    ASSERT_TRUE(loss.Evaluate(rendered, s.views.images[v], &value, &grad).ok());
    ASSERT_TRUE(RenderBackward(grad.pixels.data(), nullptr, &context, outputs, &workspace).ok());
    for (size_t i = 0; i < n; ++i) {
      if (context.splats.radius[offset + i] == 0.0f) continue;
      sum[i] += ViewspaceGradientNorm(&mean2d[2 * (offset + i)], kWidth, kHeight);
      ++seen[i];
    }
  }
  ASSERT_EQ(measured.size(), n);
  float largest = 0;
  for (size_t i = 0; i < n; ++i) largest = std::max(largest, sum[i]);
  ASSERT_GT(largest, 0.0f);
  int nonzero = 0;
  for (size_t i = 0; i < n; ++i) {
    const float expected = seen[i] ? sum[i] / static_cast<float>(seen[i]) : 0.0f;
    EXPECT_NEAR(measured[i], expected, 1e-4f * largest) << "Gaussian " << i;
    nonzero += measured[i] > 0;
  }
  EXPECT_GT(nonzero, 50);
}

}  // namespace
}  // namespace m4d
