// The random start of keyframe training: points uniform in the cameras' box, as the reference
// draws them, but only where at least two views look, coloured with what those views see
// there. The reference's start (random colours, half of it where no view looks) lost most of
// its Gaussians to pruning before densification could use them: on the realistic scene
// without points 32,640 became 4,790 (docs/results/2026-11-29-quality-per-minute.md).
#ifndef M4D_ENCODER_TRAIN_RANDOM_START_H_
#define M4D_ENCODER_TRAIN_RANDOM_START_H_

#include <cstddef>
#include <cstdint>

#include "encoder/src/capture/point_cloud.h"
#include "encoder/src/train/training_views.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct RandomStartOptions {
  size_t points = 100000;
  int min_views = 2;  // at most the views there are
  // Draws per point wanted before giving up on the views: where they see little of the box
  // the rest of the points are drawn anywhere in it, with the mean colour of the kept ones.
  int max_draws_per_point = 64;
  uint64_t seed = 0;
};

// `options.points` points in the box [lo, hi].
Status ViewedRandomPoints(const TrainingViews& views, const float lo[3], const float hi[3],
                          const RandomStartOptions& options, PointCloud* points);

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_RANDOM_START_H_
