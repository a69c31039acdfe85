#include "sdk/src/render/camera.h"

#include <cmath>

namespace m4d {
namespace {

bool AllFinite(const float* v, int n) {
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) return false;
  }
  return true;
}

bool IsRotation(const float* r) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double dot = static_cast<double>(r[3 * i]) * r[3 * j] +
                         static_cast<double>(r[3 * i + 1]) * r[3 * j + 1] +
                         static_cast<double>(r[3 * i + 2]) * r[3 * j + 2];
      if (std::fabs(dot - (i == j ? 1.0 : 0.0)) > 1e-3) return false;
    }
  }
  const double det = r[0] * (static_cast<double>(r[4]) * r[8] - static_cast<double>(r[5]) * r[7]) -
                     r[1] * (static_cast<double>(r[3]) * r[8] - static_cast<double>(r[5]) * r[6]) +
                     r[2] * (static_cast<double>(r[3]) * r[7] - static_cast<double>(r[4]) * r[6]);
  return det > 0;
}

}  // namespace

Status ValidateCamera(const Camera& camera) {
  if (camera.width < 1 || camera.height < 1 || camera.width > kMaxImageSide ||
      camera.height > kMaxImageSide ||
      static_cast<long long>(camera.width) * camera.height > kMaxImagePixels) {
    return Status(M4D_ERR_INVALID_ARG, "camera: image size out of range");
  }
  if (!(camera.fx > 0) || !(camera.fy > 0) || !std::isfinite(camera.fx) ||
      !std::isfinite(camera.fy) || !std::isfinite(camera.cx) || !std::isfinite(camera.cy)) {
    return Status(M4D_ERR_INVALID_ARG, "camera: focal lengths must be positive and finite");
  }
  if (!AllFinite(camera.rotation, 9) || !AllFinite(camera.translation, 3) ||
      !IsRotation(camera.rotation)) {
    return Status(M4D_ERR_INVALID_ARG, "camera: transform is not a finite rigid motion");
  }
  if (!(camera.near_plane > 0) || !std::isfinite(camera.near_plane)) {
    return Status(M4D_ERR_INVALID_ARG, "camera: near plane must be positive");
  }
  return Status::Ok();
}

void CameraCentre(const Camera& camera, float centre[3]) {
  const float* r = camera.rotation;
  const float* t = camera.translation;
  for (int a = 0; a < 3; ++a) {
    centre[a] = -(r[a] * t[0] + r[3 + a] * t[1] + r[6 + a] * t[2]);
  }
}

}  // namespace m4d
