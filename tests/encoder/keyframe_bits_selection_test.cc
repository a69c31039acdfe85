// The keyframe bits selection (train/keyframe_bits_selection.h): every candidate is coded and
// judged on the held-out views, and the bound per halving decides how far down the ladder it goes.
#include "encoder/src/train/keyframe_bits_selection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "encoder/src/pipeline/rate_points.h"
#include "encoder/src/train/view_evaluation.h"
#include "tests/raster/splat_test_scenes.h"

namespace m4d {
namespace {

constexpr int kWidth = 64, kHeight = 48;

// 1500 small coloured Gaussians of SH degree 1 in a cube, and one view of them as its image: a
// model that renders its view exactly, so only quantization costs PSNR.
HeldOutModel SceneAndItsView() {
  HeldOutModel held_out;
  GaussianModel& model = held_out.model;
  model.sh_degree = 1;
  model.Resize(1500);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  const size_t sh = model.sh.size() / model.size();
  for (size_t i = 0; i < model.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      model.positions[3 * i + a] = unit(random);
      model.log_scales[3 * i + a] = std::log(0.03f) + 0.5f * unit(random);
    }
    for (size_t k = 0; k < sh; ++k) model.sh[sh * i + k] = (k < 3 ? 1.0f : 0.2f) * unit(random);
    for (int k = 0; k < 4; ++k) model.rotations[4 * i + k] = unit(random);
    model.opacity_logits[i] = 2.0f * unit(random);
  }
  const float eye[3] = {0, 0, -4}, target[3] = {0, 0, 0};
  held_out.settings.threads = 1;
  held_out.settings.sh_degree = 1;
  TrainingViews& views = held_out.validation;
  views.camera_indices = {0};
  views.cameras = {test::LookAtCamera(kWidth, kHeight, 60.0f, 0, 0, eye, target)};
  views.images.emplace_back();
  RenderContext context;
  EXPECT_TRUE(
      RenderView(model, views.cameras[0], held_out.settings, &context, &views.images[0]).ok());
  return held_out;
}

TEST(KeyframeBitsSelection, CandidatesAreThePointAndTheCoarserOnes) {
  const std::vector<KeyframeBitsCandidate> r4 = KeyframeBitsCandidates("r4");
  ASSERT_EQ(r4.size(), 4u);
  EXPECT_EQ(r4[0].name, "r4");
  EXPECT_EQ(r4[3].name, "r1");
  RatePointSettings point;
  ASSERT_TRUE(FindRatePoint("r2", &point).ok());
  EXPECT_EQ(QuantizationName(r4[2].quantization), QuantizationName(point.keyframe));
  EXPECT_EQ(KeyframeBitsCandidates("r1").size(), 1u);
  EXPECT_TRUE(KeyframeBitsCandidates("r9").empty());
}

TEST(KeyframeBitsSelection, TheBoundDecidesHowFarDownTheLadder) {
  const HeldOutModel held_out = SceneAndItsView();
  const std::vector<KeyframeBitsCandidate> candidates = KeyframeBitsCandidates("r5");
  KeyframeBitsChoice strict, loose;
  ASSERT_TRUE(SelectKeyframeBits(held_out, candidates, 0.0, &strict).ok());
  ASSERT_TRUE(SelectKeyframeBits(held_out, candidates, 1000.0, &loose).ok());
  ASSERT_EQ(strict.trials.size(), candidates.size());
  const KeyframeBitsTrial& finest = strict.trials.front();
  const KeyframeBitsTrial& coarsest = strict.trials.back();
  EXPECT_LT(coarsest.bytes, finest.bytes);
  EXPECT_LT(coarsest.psnr, finest.psnr);  // the model renders its view exactly: bits cost PSNR
  EXPECT_EQ(finest.gaussians, held_out.model.size());
  EXPECT_EQ(strict.chosen, 0);  // no loss allowed: the rate point's own bits
  EXPECT_EQ(loose.chosen, static_cast<int>(candidates.size()) - 1);  // any loss: the cheapest
}

TEST(KeyframeBitsSelection, NoHeldOutViewsNoTrial) {
  HeldOutModel held_out = SceneAndItsView();
  held_out.validation = TrainingViews();
  KeyframeBitsChoice choice;
  ASSERT_TRUE(SelectKeyframeBits(held_out, KeyframeBitsCandidates("r4"), 1000.0, &choice).ok());
  EXPECT_EQ(choice.chosen, 0);
  EXPECT_TRUE(choice.trials.empty());
}

}  // namespace
}  // namespace m4d
