#include "encoder/src/pipeline/encoder_options.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "encoder/src/capture/up_axis_estimate.h"

namespace m4d {

Status ValidateEncoderOptions(const EncoderOptions& o) {
  auto bad = [](const char* what) {
    return Status(M4D_ERR_INVALID_ARG, std::string("encoder options: ") + what);
  };
  if (o.sh_degree < 0 || o.sh_degree > 3) return bad("SH degree must be 0..3");
  if (o.up_axis < kUpAxisAuto || o.up_axis > 6) return bad("up axis must be auto or 0..6");
  if (o.first_frame < 0 || o.frame_count < 0) return bad("negative frame range");
  if (o.lookahead_frames < 1) return bad("lookahead must be at least one frame");
  if (o.lookahead_step < 1) return bad("lookahead step must be at least one frame");
  if (o.retrain_iterations < 1) return bad("retrain iterations must be positive");
  if (o.first_motion_iterations < 0 || o.motion.iterations < 0) return bad("motion iterations");
  if (!(o.motion_rate_decay >= 0 && o.motion_rate_decay <= 1)) return bad("motion rate decay");
  if (o.gop.max_length < 1 || o.gop.min_length < 1 || o.gop.fixed_length < 0) {
    return bad("GOP lengths");
  }
  if (!(o.gop.threshold >= 0.0f)) return bad("GOP threshold");
  if (!std::is_sorted(o.gop.starts.begin(), o.gop.starts.end())) return bad("GOP starts");
  if (!(o.gop.random_access_seconds >= 0.0 && o.gop.random_access_seconds <= 1e6)) {
    return bad("random-access interval");
  }
  if (!std::isfinite(o.compensation_min_gain)) return bad("compensation minimum gain");
  if (!std::isfinite(o.motion_min_gain)) return bad("motion minimum gain");
  for (int l = 0; l < o.grid.num_levels; ++l) {
    if (!(o.grid_steps[l] > 0.0f)) return bad("grid steps must be positive");
  }
  return ValidateTrainingOptions(o.keyframe);
}

}  // namespace m4d
