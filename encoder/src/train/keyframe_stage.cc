#include "encoder/src/train/keyframe_stage.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "encoder/src/train/background_shell.h"
#include "encoder/src/train/photo_consistent_points.h"
#include "encoder/src/train/point_initialisation.h"
#include "encoder/src/train/random_start.h"
#include "encoder/src/train/random_start_schedule.h"
#include "encoder/src/train/scene_extent.h"

namespace m4d {
namespace {

constexpr size_t kAdcRandomStartDivisor = 10;

// Photo-consistent points seen by at least `min_views` views.
Status PhotoConsistentStart(const TrainingViews& views, const KeyframeTrainingOptions& options,
                            size_t points, int min_views, PointCloud* cloud) {
  PhotoConsistencyOptions photo;
  photo.points = points;
  photo.min_views = min_views;
  photo.seed = options.context.seed;
  photo.threads = options.context.threads;
  return PhotoConsistentPoints(views, photo, cloud);
}

// Points uniform in the part of the cameras' box the views see (random_start.h).
Status RandomStart(const TrainingViews& views, const KeyframeTrainingOptions& options,
                   size_t points, const PointInitialisationOptions& init, GaussianModel* initial) {
  const SceneBounds bounds = CameraSceneBounds(views.cameras);
  float lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = bounds.centre[a] - bounds.extent;
    hi[a] = bounds.centre[a] + bounds.extent;
  }
  RandomStartOptions random;
  random.points = points;
  random.seed = options.context.seed;
  PointCloud cloud;
  M4D_RETURN_IF_ERROR(ViewedRandomPoints(views, lo, hi, random, &cloud));
  return InitialiseFromPoints(cloud, init, initial);
}

// The shell's points (background_shell.h), at most `limit` of them spread over the sphere.
Status ShellPoints(const TrainingViews& views, size_t requested, size_t limit, PointCloud* points) {
  BackgroundShellOptions shell;
  shell.points = requested;
  M4D_RETURN_IF_ERROR(BackgroundShellPoints(views, shell, points));
  if (points->size() <= limit) return Status::Ok();
  // Every k-th of them, evenly over the sphere (the Fibonacci order runs pole to pole).
  PointCloud kept;
  for (size_t i = 0; i < limit; ++i) {
    const size_t row = i * points->size() / limit;
    kept.positions.insert(kept.positions.end(), &points->positions[3 * row],
                          &points->positions[3 * row] + 3);
    kept.colors.insert(kept.colors.end(), &points->colors[3 * row], &points->colors[3 * row] + 3);
  }
  *points = std::move(kept);
  return Status::Ok();
}

// How many of `wanted` points a random start draws. ADC grows the model where its gradients
// ask, up to the cap, so a random start as large as the cap leaves it no room: it starts from a
// tenth, about the reference's proportion (100k random points for models that grow to a
// million). MCMC grows by a few percent per refinement and would not reach its budget from a
// tenth within the short schedule, so it starts full (docs/design/densification_strategies.md).
size_t RandomStartCount(size_t wanted, DensificationStrategyKind strategy) {
  if (strategy == DensificationStrategyKind::kMcmc) return wanted;
  return std::max<size_t>(wanted / kAdcRandomStartDivisor, 1);
}

// The chain without the shell.
Status ChainOfStarts(const TrainingViews& views, const KeyframeTrainingOptions& options,
                     const PointInitialisationOptions& init, size_t start_points,
                     GaussianModel* initial, std::vector<KeyframeStart>* tried) {
  const size_t enough = std::min(kMinStartPoints, std::max<size_t>(start_points / 2, 1));
  PointCloud found;  // the most points a sweep found, kept in the random start
  if (!options.random_initialisation) {
    const size_t asked = std::max<size_t>(
        static_cast<size_t>(std::lround(static_cast<double>(start_points) * options.sweep_share)),
        1);
    for (int min_views : {3, 2}) {
      PointCloud points;
      M4D_RETURN_IF_ERROR(PhotoConsistentStart(views, options, asked, min_views, &points));
      const bool taken = points.size() >= std::min(enough, asked);
      tried->push_back({"photo-consistent points, " + std::to_string(min_views) + " views",
                        points.size(), taken});
      if (taken) return InitialiseFromPoints(points, init, initial);
      if (points.size() > found.size()) found = std::move(points);
    }
  }
  GaussianModel random;
  GaussianModel* box = found.size() > 0 ? &random : initial;
  const size_t drawn = RandomStartCount(start_points - found.size(), options.strategy);
  M4D_RETURN_IF_ERROR(RandomStart(views, options, drawn, init, box));
  if (found.size() > 0) {
    GaussianModel swept;
    M4D_RETURN_IF_ERROR(InitialiseFromPoints(found, init, &swept));
    swept.Append(random);
    *initial = std::move(swept);
  }
  tried->push_back({found.size() > 0 ? "random in the cameras' box, with the points found"
                                     : "random in the cameras' box",
                    initial->size(), true, true});
  return Status::Ok();
}

}  // namespace

Status InitialKeyframeModel(const Capture& capture, const TrainingViews& views,
                            const KeyframeTrainingOptions& options, GaussianModel* initial,
                            std::vector<KeyframeStart>* tried) {
  std::vector<KeyframeStart> starts;
  if (tried == nullptr) tried = &starts;
  tried->clear();
  PointInitialisationOptions init;
  init.threads = options.context.threads;
  init.sh_degree = options.sh_degree;
  // The MCMC paper starts every Gaussian half opaque: relocation needs opaque ones to sample.
  if (options.strategy == DensificationStrategyKind::kMcmc) init.opacity = 0.5f;
  if (capture.initial_points.size() > 0) {
    tried->push_back({"capture points", capture.initial_points.size(), true});
    return InitialiseFromPoints(capture.initial_points, init, initial);
  }
  const size_t start_points = std::min(options.random_points, GaussianCap(options, views));
  // The shell takes at most a quarter of the start, and comes after the chain's points.
  PointCloud shell;
  if (options.background_shell_points > 0) {
    M4D_RETURN_IF_ERROR(
        ShellPoints(views, options.background_shell_points, start_points / 4, &shell));
  }
  M4D_RETURN_IF_ERROR(
      ChainOfStarts(views, options, init, start_points - shell.size(), initial, tried));
  if (shell.size() == 0) return Status::Ok();
  tried->push_back({"background shell", shell.size(), true});
  GaussianModel background;
  M4D_RETURN_IF_ERROR(InitialiseFromPoints(shell, init, &background));
  initial->Append(background);
  return Status::Ok();
}

Status TrainKeyframe(const Capture& capture, int frame, const KeyframeTrainingOptions& options,
                     const ProgressCallback& progress, GaussianModel* model,
                     KeyframeTrainingReport* report, const TrainerObserver& observe) {
  M4D_RETURN_IF_ERROR(ValidateTrainingOptions(options));
  TrainingViews views;
  M4D_RETURN_IF_ERROR(LoadTrainingViews(capture, frame, capture.TrainCameras(), &views));
  GaussianModel initial;
  std::vector<KeyframeStart> starts;
  M4D_RETURN_IF_ERROR(InitialKeyframeModel(capture, views, options, &initial, &starts));
  const KeyframeTrainingOptions trained = OptionsForStart(options, starts);
  KeyframeTrainer trainer;
  M4D_RETURN_IF_ERROR(trainer.Init(trained, std::move(views), std::move(initial)));
  if (observe) {
    while (trainer.iteration() < options.iterations) {
      M4D_RETURN_IF_ERROR(trainer.TrainUntil(trainer.iteration() + kObserveEvery, progress));
      M4D_RETURN_IF_ERROR(observe(&trainer));
    }
  } else {
    M4D_RETURN_IF_ERROR(trainer.Train(progress));
  }
  if (report != nullptr) {
    report->random_start_schedule = TakesRandomStartSchedule(options, starts);
    report->starts = std::move(starts);
    report->tenths = trainer.tenths();
    report->counts = trainer.densify_totals();
    report->largest_removal = trainer.largest_removal();
  }
  *model = trainer.TakeModel();
  return Status::Ok();
}

}  // namespace m4d
