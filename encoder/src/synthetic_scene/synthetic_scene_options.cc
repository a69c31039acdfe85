#include "synthetic_scene/synthetic_scene_options.h"

#include <string>

namespace m4d {
namespace {

Status CheckRange(const char* name, long long value, long long low, long long high) {
  if (value >= low && value <= high) return Status::Ok();
  return Status(M4D_ERR_INVALID_ARG, std::string("synthetic scene: ") + name + " is " +
                                         std::to_string(value) + ", must be in [" +
                                         std::to_string(low) + ", " + std::to_string(high) + "]");
}

}  // namespace

Status ValidateSyntheticSceneOptions(const SyntheticSceneOptions& o) {
  M4D_RETURN_IF_ERROR(CheckRange("cameras", o.cameras, 1, kMaxSyntheticCameras));
  M4D_RETURN_IF_ERROR(CheckRange("width", o.width, 8, kMaxSyntheticSide));
  M4D_RETURN_IF_ERROR(CheckRange("height", o.height, 8, kMaxSyntheticSide));
  M4D_RETURN_IF_ERROR(CheckRange("frames", o.frames, 1, kMaxSyntheticFrames));
  M4D_RETURN_IF_ERROR(CheckRange("points", o.points, 0, kMaxSyntheticPoints));
  M4D_RETURN_IF_ERROR(CheckRange("supersample", o.supersample, 1, 4));
  M4D_RETURN_IF_ERROR(CheckRange("msaa samples", o.msaa_samples, 1, 16));
  if (o.emergent_frame != -1) {
    M4D_RETURN_IF_ERROR(CheckRange("emergent frame", o.emergent_frame, 0, o.frames - 1));
  }
  if (o.background_change_frame != -1) {
    M4D_RETURN_IF_ERROR(
        CheckRange("background change frame", o.background_change_frame, 0, o.frames - 1));
  }
  if (o.width * o.supersample > kMaxSyntheticSide * 2 ||
      o.height * o.supersample > kMaxSyntheticSide * 2) {
    return Status(M4D_ERR_LIMIT, "synthetic scene: supersampled render above " +
                                     std::to_string(kMaxSyntheticSide * 2) + " pixels a side");
  }
  if (!(o.horizontal_fov_degrees > 10.0f && o.horizontal_fov_degrees < 150.0f)) {
    return Status(M4D_ERR_INVALID_ARG,
                  "synthetic scene: horizontal field of view must be in (10, 150) degrees");
  }
  return Status::Ok();
}

int EmergentFrame(const SyntheticSceneOptions& options) {
  return options.emergent_frame >= 0 ? options.emergent_frame : options.frames / 2;
}

}  // namespace m4d
