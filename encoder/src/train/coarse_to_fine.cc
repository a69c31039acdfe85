#include "encoder/src/train/coarse_to_fine.h"

#include <algorithm>
#include <cstdint>

#include "encoder/src/capture/camera_downscale.h"
#include "encoder/src/image/area_resize.h"

namespace m4d {
namespace {

bool KeepsMinimumSide(const TrainingViews& views, int factor) {
  return std::all_of(views.cameras.begin(), views.cameras.end(), [factor](const Camera& c) {
    return c.width / factor >= kMinCoarseViewSide && c.height / factor >= kMinCoarseViewSide;
  });
}

Status DownscaleViews(const TrainingViews& views, int factor, TrainingViews* out) {
  *out = TrainingViews();
  out->camera_indices = views.camera_indices;
  out->cameras = views.cameras;
  out->images.resize(views.images.size());
  for (int v = 0; v < views.size(); ++v) {
    Camera& camera = out->cameras[static_cast<size_t>(v)];
    M4D_RETURN_IF_ERROR(DownscaleCamera(factor, &camera));
    M4D_RETURN_IF_ERROR(ResizeArea(views.images[static_cast<size_t>(v)], camera.width,
                                   camera.height, &out->images[static_cast<size_t>(v)]));
  }
  return Status::Ok();
}

}  // namespace

Status ValidateCoarseToFine(const CoarseToFineSchedule& schedule) {
  if (schedule.levels < 0 || schedule.levels > kMaxCoarseLevels) {
    return Status(M4D_ERR_INVALID_ARG, "coarse-to-fine levels must be in [0, 4]");
  }
  if (schedule.until < 0) return Status(M4D_ERR_INVALID_ARG, "negative coarse-to-fine end");
  return Status::Ok();
}

Status ViewPyramid::Build(const TrainingViews& views, const CoarseToFineSchedule& schedule) {
  M4D_RETURN_IF_ERROR(ValidateCoarseToFine(schedule));
  schedule_ = schedule;
  levels_.clear();
  for (int level = 1; level <= schedule.levels && KeepsMinimumSide(views, 1 << level); ++level) {
    levels_.emplace_back();
    M4D_RETURN_IF_ERROR(DownscaleViews(views, 1 << level, &levels_.back()));
  }
  return Status::Ok();
}

const TrainingViews* ViewPyramid::At(int iteration) const {
  if (levels_.empty() || iteration >= schedule_.until || iteration < 1) return nullptr;
  // Part k of the window, counted from the coarsest, runs at level `schedule.levels - k`,
  // clamped to the coarsest level built.
  const int64_t part =
      static_cast<int64_t>(iteration - 1) * schedule_.levels / (schedule_.until - 1);
  const int level = std::min(schedule_.levels - static_cast<int>(part), levels());
  return &levels_[static_cast<size_t>(level - 1)];
}

}  // namespace m4d
