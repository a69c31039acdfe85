#include "encoder/src/synthetic/synthetic_scene_options.h"

#include <cmath>
#include <string>

namespace m4d {
namespace {

Status CheckRange(const char* name, long long value, long long low, long long high) {
  if (value >= low && value <= high) return Status::Ok();
  return Status(M4D_ERR_INVALID_ARG, std::string("synthetic scene: ") + name + " is " +
                                         std::to_string(value) + ", must be in [" +
                                         std::to_string(low) + ", " + std::to_string(high) + "]");
}

Status CheckStrength(const char* name, float value, float low, float high) {
  if (value >= low && value <= high) return Status::Ok();
  return Status(M4D_ERR_INVALID_ARG, std::string("synthetic scene: ") + name + " is " +
                                         std::to_string(value) + ", must be in [" +
                                         std::to_string(low) + ", " + std::to_string(high) + "]");
}

// The radial part r (1 + k1 r^2 + k2 r^4) must grow with r until it passes the image's
// corner (with room for the tangential terms), or the distortion folds the image over and
// has no inverse; and the pinhole radius it takes must stay within twice the corner's, which
// bounds the wider canvas the pinhole view is rendered on.
Status CheckLensFolds(const SyntheticSceneOptions& o) {
  const CaptureRealism& r = o.realism;
  const double aspect = static_cast<double>(o.height) / o.width;
  const double corner = std::tan(0.5 * o.horizontal_fov_degrees * 3.14159265358979 / 180.0) *
                        std::sqrt(1.0 + aspect * aspect);
  const double step = corner / 1000.0;
  for (double radius = step; radius <= 2.0 * corner; radius += step) {
    const double r2 = radius * radius;
    if (1.0 + 3.0 * r.k1 * r2 + 5.0 * r.k2 * r2 * r2 <= 0.0) break;
    if (radius * (1.0 + r.k1 * r2 + r.k2 * r2 * r2) >= 1.1 * corner) return Status::Ok();
  }
  return Status(M4D_ERR_INVALID_ARG,
                "synthetic scene: lens distortion k1 " + std::to_string(r.k1) + ", k2 " +
                    std::to_string(r.k2) +
                    " folds or stretches the image too far for this field of view");
}

Status ValidateRealism(const SyntheticSceneOptions& o) {
  const CaptureRealism& r = o.realism;
  M4D_RETURN_IF_ERROR(CheckStrength("noise sigma", r.noise_sigma, 0.0f, 50.0f));
  M4D_RETURN_IF_ERROR(CheckRange("jpeg quality", r.jpeg_quality, 0, 100));
  M4D_RETURN_IF_ERROR(CheckStrength("exposure spread", r.exposure_spread, 0.0f, 0.5f));
  M4D_RETURN_IF_ERROR(CheckStrength("white balance spread", r.white_balance_spread, 0.0f, 0.5f));
  M4D_RETURN_IF_ERROR(CheckStrength("k1", r.k1, -1.0f, 1.0f));
  M4D_RETURN_IF_ERROR(CheckStrength("k2", r.k2, -1.0f, 1.0f));
  M4D_RETURN_IF_ERROR(CheckStrength("p1", r.p1, -0.05f, 0.05f));
  M4D_RETURN_IF_ERROR(CheckStrength("p2", r.p2, -0.05f, 0.05f));
  M4D_RETURN_IF_ERROR(CheckStrength("sparse rig arc", r.sparse_rig_arc_degrees, 1.0f, 180.0f));
  M4D_RETURN_IF_ERROR(CheckStrength("background sway", r.background_sway, 0.0f, 0.3f));
  M4D_RETURN_IF_ERROR(CheckStrength("light flicker", r.light_flicker, 0.0f, 0.5f));
  return CheckLensFolds(o);
}

}  // namespace

SyntheticSceneOptions SyntheticSceneOptions::Realistic() {
  SyntheticSceneOptions o;
  o.cameras = 4;
  CaptureRealism& r = o.realism;
  r.noise_sigma = 2.0f;
  r.jpeg_quality = 90;
  r.exposure_spread = 0.08f;
  r.white_balance_spread = 0.04f;
  r.k1 = -0.12f;
  r.k2 = 0.03f;
  r.p1 = 0.001f;
  r.p2 = -0.0005f;
  r.left_handed = true;
  r.sparse_rig = true;
  r.background_sway = 0.03f;
  r.light_flicker = 0.02f;
  return o;
}

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
  return ValidateRealism(o);
}

int EmergentFrame(const SyntheticSceneOptions& options) {
  return options.emergent_frame >= 0 ? options.emergent_frame : options.frames / 2;
}

}  // namespace m4d
