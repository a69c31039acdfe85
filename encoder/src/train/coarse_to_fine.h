// Coarse-to-fine training resolution: the first iterations of a keyframe training fit the
// views area-averaged by 2^levels, then by half as much, ..., then at full size. Small views
// cost less to rasterize, and a start far from the scene might be pulled to the low
// frequencies before it fits each pixel with a floater. Densification reads the 2D gradient in
// normalised device units (viewspace_gradient.h), which do not depend on the view's size for
// Gaussians wider than a pixel; smaller ones get larger gradients on coarse views, and the
// model grows more. Off by default, by measurement (docs/design/densification_strategies.md).
#ifndef M4D_ENCODER_TRAIN_COARSE_TO_FINE_H_
#define M4D_ENCODER_TRAIN_COARSE_TO_FINE_H_

#include <vector>

#include "encoder/src/train/training_views.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct CoarseToFineSchedule {
  int levels = 0;  // 0: every iteration at full size; at most kMaxCoarseLevels
  int until = 0;   // the first iteration at full size; [1, until) is split evenly over the levels
};

constexpr int kMaxCoarseLevels = 4;
// A level is skipped when it would leave a view narrower or lower than this many pixels.
constexpr int kMinCoarseViewSide = 16;

// M4D_ERR_INVALID_ARG for levels outside [0, kMaxCoarseLevels] or a negative until.
Status ValidateCoarseToFine(const CoarseToFineSchedule& schedule);

// The views of each level: level l holds every view area-averaged by 2^l, for l = 1 up to the
// schedule's levels or the last level whose views all keep kMinCoarseViewSide pixels a side.
class ViewPyramid {
 public:
  Status Build(const TrainingViews& views, const CoarseToFineSchedule& schedule);
  // The views iteration `iteration` (1-based) fits, or null for the full-size ones.
  const TrainingViews* At(int iteration) const;
  int levels() const { return static_cast<int>(levels_.size()); }

 private:
  CoarseToFineSchedule schedule_;
  std::vector<TrainingViews> levels_;  // levels_[l - 1] is level l
};

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_COARSE_TO_FINE_H_
