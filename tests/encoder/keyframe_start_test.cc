// Keyframe training from any start (keyframe_trainer.h, InitialKeyframeModel): a sparse rig
// without points is never refused, every start of the chain trains with either densification
// strategy without losing most of its Gaussians at once, and a random start ends near the
// photo-consistent one. On the realistic built-in scene, small: 4 cameras of 80x60, all
// trained on (a held-out view of so sparse and small a rig scores about the same whatever the
// start, and tells them apart by noise alone).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "encoder/src/synthetic/synthetic_capture.h"
#include "encoder/src/train/keyframe_stage.h"
#include "encoder/src/train/keyframe_trainer.h"

namespace m4d {
namespace {

Capture SparseCaptureWithoutPoints() {
  SyntheticSceneOptions scene = SyntheticSceneOptions::Realistic();
  scene.width = 80;
  scene.height = 60;
  scene.frames = 1;
  scene.points = 0;
  Capture capture;
  EXPECT_TRUE(GenerateSyntheticCapture(scene, &capture, nullptr).ok());
  EXPECT_EQ(capture.initial_points.size(), 0u);
  capture.test_cameras.clear();
  return capture;
}

KeyframeTrainingOptions Options(DensificationStrategyKind strategy, bool random) {
  KeyframeTrainingOptions o = KeyframeTrainingOptions::Short(300);
  o.sh_degree = 1;
  o.strategy = strategy;
  o.random_initialisation = random;
  o.random_points = 3000;
  // The starts compared alone: the shell joins the default start, not the random one.
  o.background_shell_points = 0;
  o.quantization_aware_iterations = 0;
  o.context.seed = 2;
  o.context.threads = 2;
  return o;
}

struct StartRun {
  KeyframeTrainingReport report;
  double psnr = 0;  // on the training views
};

double TrainingViewsPsnr(const Capture& capture, const GaussianModel& model) {
  TrainingViews views;
  EXPECT_TRUE(LoadTrainingViews(capture, 0, capture.TrainCameras(), &views).ok());
  RenderSettings settings;
  settings.threads = 2;
  settings.sh_degree = 1;
  EvaluationResult quality;
  EXPECT_TRUE(EvaluateViews(model, views, settings, nullptr, &quality).ok());
  return quality.mean_psnr;
}

StartRun Train(const Capture& capture, const KeyframeTrainingOptions& options) {
  StartRun run;
  GaussianModel model;
  EXPECT_TRUE(TrainKeyframe(capture, 0, options, nullptr, &model, &run.report).ok());
  run.psnr = TrainingViewsPsnr(capture, model);
  return run;
}

TEST(KeyframeStartTest, EveryStartTrainsWithoutCollapse) {
  const Capture capture = SparseCaptureWithoutPoints();
  for (auto strategy :
       {DensificationStrategyKind::kAdaptiveDensityControl, DensificationStrategyKind::kMcmc}) {
    double psnr[2] = {0, 0};
    for (bool random : {false, true}) {
      const StartRun run = Train(capture, Options(strategy, random));
      const std::string what = std::string(StrategyName(strategy)) + (random ? " random" : "");
      const KeyframeTrainingReport& r = run.report;
      ASSERT_FALSE(r.starts.empty()) << what;
      EXPECT_TRUE(r.starts.back().taken) << what;
      for (size_t i = 0; i + 1 < r.starts.size(); ++i) EXPECT_FALSE(r.starts[i].taken) << what;
      EXPECT_EQ(r.starts.back().name.rfind("random in the cameras' box", 0) == 0,
                r.starts.size() > 2 || random)
          << what;
      EXPECT_EQ(r.random_start_schedule,
                r.starts.back().name.rfind("random in the cameras' box", 0) == 0 &&
                    strategy == DensificationStrategyKind::kAdaptiveDensityControl)
          << what;
      // No event removed more than half of the model, and it never fell to a quarter of its
      // largest size.
      EXPECT_LE(r.largest_removal, 0.5) << what;
      ASSERT_EQ(r.tenths.size(), 10u) << what;
      size_t largest = 0;
      for (const TrainingTenth& t : r.tenths) {
        largest = std::max(largest, t.gaussians);
        EXPECT_GE(4 * t.gaussians, largest) << what << " at " << t.iteration;
      }
      psnr[random] = run.psnr;
    }
    // With MCMC the random start ends near the chain's. With adaptive density control the
    // chain falls through to random points here too, keeping the few the sweep found, and both
    // take the random start's schedule, so the sweep's points lead at this size; on the
    // realistic scene at 240x136 the chain's start is the sweep's and the random start ends a
    // little under it (docs/results/2026-11-29-random-start-schedule.md).
    if (strategy == DensificationStrategyKind::kMcmc) {
      EXPECT_GT(psnr[1], psnr[0] - 1.5) << StrategyName(strategy) << " " << psnr[0];
    }
  }
}

// The random start's schedule (random_start_schedule.h) recovers a random start: the same start
// trained at the plain short schedule ends well under it.
TEST(KeyframeStartTest, TheRandomStartsScheduleLiftsARandomStart) {
  const Capture capture = SparseCaptureWithoutPoints();
  const KeyframeTrainingOptions options =
      Options(DensificationStrategyKind::kAdaptiveDensityControl, true);
  const StartRun scheduled = Train(capture, options);
  ASSERT_TRUE(scheduled.report.random_start_schedule);

  TrainingViews views;
  ASSERT_TRUE(LoadTrainingViews(capture, 0, capture.TrainCameras(), &views).ok());
  GaussianModel initial;
  ASSERT_TRUE(InitialKeyframeModel(capture, views, options, &initial).ok());
  KeyframeTrainer plain;
  ASSERT_TRUE(plain.Init(options, views, std::move(initial)).ok());
  ASSERT_TRUE(plain.Train().ok());
  EXPECT_GT(scheduled.psnr, TrainingViewsPsnr(capture, plain.model()) + 1.0);
}

// A rig too sparse for points seen by 3 views falls through the chain, each start reported.
TEST(KeyframeStartTest, AChainOfStartsNeverRefuses) {
  Capture capture = SparseCaptureWithoutPoints();
  capture.test_cameras = {0, 1};  // two training views left
  TrainingViews views;
  ASSERT_TRUE(LoadTrainingViews(capture, 0, capture.TrainCameras(), &views).ok());
  KeyframeTrainingOptions options = Options(DensificationStrategyKind::kMcmc, false);
  options.background_shell_points = 20000;
  GaussianModel initial;
  std::vector<KeyframeStart> tried;
  ASSERT_TRUE(InitialKeyframeModel(capture, views, options, &initial, &tried).ok());
  ASSERT_GE(tried.size(), 2u);
  EXPECT_EQ(tried[0].name, "photo-consistent points, 3 views");
  EXPECT_FALSE(tried[0].taken);  // two views cannot see a point three times
  // The chain's start, then the background shell, both taken and both in the model.
  ASSERT_EQ(tried.back().name, "background shell");
  const KeyframeStart& chain = tried[tried.size() - 2];
  EXPECT_TRUE(chain.taken);
  EXPECT_TRUE(tried.back().taken);
  EXPECT_GT(tried.back().points, 0u);
  EXPECT_LE(4 * tried.back().points, initial.size());  // at most a quarter of the start
  EXPECT_EQ(initial.size(), chain.points + tried.back().points);
}

// A random start leaves ADC room to grow (a tenth of the count); MCMC, which cannot grow that
// far in a short schedule, starts from all of it.
TEST(KeyframeStartTest, ARandomStartLeavesAdcRoomToGrow) {
  const Capture capture = SparseCaptureWithoutPoints();
  TrainingViews views;
  ASSERT_TRUE(LoadTrainingViews(capture, 0, capture.TrainCameras(), &views).ok());
  size_t drawn[2] = {0, 0};
  for (auto strategy :
       {DensificationStrategyKind::kAdaptiveDensityControl, DensificationStrategyKind::kMcmc}) {
    GaussianModel initial;
    std::vector<KeyframeStart> tried;
    ASSERT_TRUE(
        InitialKeyframeModel(capture, views, Options(strategy, true), &initial, &tried).ok());
    ASSERT_EQ(tried.size(), 1u);  // no shell in these options
    EXPECT_EQ(initial.size(), tried[0].points);
    drawn[strategy == DensificationStrategyKind::kMcmc] = initial.size();
  }
  EXPECT_EQ(drawn[1], 3000u);  // Options' random_points, below the cap
  EXPECT_EQ(drawn[0], 300u);
}

}  // namespace
}  // namespace m4d
