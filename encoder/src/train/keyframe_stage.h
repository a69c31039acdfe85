// The keyframe stage as a whole: the start a capture's first keyframe trains from (a chain
// that never refuses a capture, and a background shell), then KeyframeTrainer's run, with a
// report of both (docs/design/densification_strategies.md).
#ifndef M4D_ENCODER_TRAIN_KEYFRAME_STAGE_H_
#define M4D_ENCODER_TRAIN_KEYFRAME_STAGE_H_

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "encoder/src/capture/capture.h"
#include "encoder/src/train/keyframe_trainer.h"
#include "sdk/src/common/status.h"

namespace m4d {

// One start InitialKeyframeModel tried, and the points it gave.
struct KeyframeStart {
  std::string name;
  size_t points = 0;
  bool taken = false;
  bool random = false;  // points drawn at random (random_start_schedule.h)
};

// The model keyframe training starts from, the first of a chain that gives enough points
// (kMinStartPoints, or what the cap allows): the capture's points; photo-consistent points of
// the views seen by 3 views (photo_consistent_points.h); the same seen by 2 views (a rig of
// 2-4 cameras); points at random in the cameras' box where two views look (random_start.h),
// which always succeeds and keeps the points the sweeps found (the box fills the rest of the
// count). Then the background shell, whatever the start. With
// options.random_initialisation the chain starts at the random box. `tried` (if not null)
// receives each start tried.
Status InitialKeyframeModel(const Capture& capture, const TrainingViews& views,
                            const KeyframeTrainingOptions& options, GaussianModel* initial,
                            std::vector<KeyframeStart>* tried = nullptr);

// A start with fewer points is passed over for the next in the chain.
constexpr size_t kMinStartPoints = 1000;

// What TrainKeyframe reports: the starts tried, the run's tenths, the strategy's counts.
struct KeyframeTrainingReport {
  std::vector<KeyframeStart> starts;
  std::vector<TrainingTenth> tenths;
  StrategyCounts counts;
  double largest_removal = 0;
  bool random_start_schedule = false;  // trained with it (random_start_schedule.h)
};

// Looks at the trainer between iterations (a quality-over-time curve); an error stops the run.
using TrainerObserver = std::function<Status(KeyframeTrainer*)>;

// The whole keyframe stage: loads the training views of `frame`, starts from
// InitialKeyframeModel, trains, and returns the model. progress, report and observe may be
// null; observe is called every kObserveEvery iterations and after the last.
Status TrainKeyframe(const Capture& capture, int frame, const KeyframeTrainingOptions& options,
                     const ProgressCallback& progress, GaussianModel* model,
                     KeyframeTrainingReport* report = nullptr,
                     const TrainerObserver& observe = nullptr);

constexpr int kObserveEvery = 10;

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_KEYFRAME_STAGE_H_
