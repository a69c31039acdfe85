// Initial points for a capture that has none (no COLMAP model, no init_pt_cld.npz): a quick
// multi-view estimate instead of points uniform in a box. Candidates are drawn on rays of the
// training views (a random pixel of a random view, inverse depth uniform between the near
// plane and far away), each is projected into every view that sees it, and the candidates
// whose colour agrees best across those views are kept, coloured by their mean. A point on a
// surface looks alike from every camera; a point in empty space or at a wrong depth lands on
// different things. Occlusion is ignored: this only has to start training near the surfaces.
//
// On the Panoptic basketball capture (27 cameras, 640x360, 2000 iterations) this is what
// keeps the keyframe from starting as a grey fog inside the dome (README, Real captures).
#ifndef M4D_ENCODER_TRAIN_PHOTO_CONSISTENT_POINTS_H_
#define M4D_ENCODER_TRAIN_PHOTO_CONSISTENT_POINTS_H_

#include <cstddef>
#include <cstdint>

#include "common/status.h"
#include "dataset/point_cloud.h"
#include "train/training_views.h"

namespace m4d {

struct PhotoConsistencyOptions {
  size_t points = 100000;         // kept
  int candidates_per_point = 16;  // drawn per kept point
  // A candidate counts only if this many views see it (in front of the near plane, inside the
  // image); 0: half the views, at least 2.
  int min_views = 0;
  // Depth range of the candidates, in multiples of the cameras' extent (scene_extent.h):
  // from the near plane to far_extents times it.
  float far_extents = 50.0f;
  uint64_t seed = 0;
  int threads = 0;
};

// M4D_ERR_INVALID_ARG for no views, a zero camera extent or bad options; the result may hold
// fewer points than asked when few candidates are seen by enough views.
Status PhotoConsistentPoints(const TrainingViews& views, const PhotoConsistencyOptions& options,
                             PointCloud* points);

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_PHOTO_CONSISTENT_POINTS_H_
