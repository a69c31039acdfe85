#include "encoder/src/dataset/world_handedness.h"

#include <string>

namespace m4d {

double RotationDeterminant(const float r[9]) {
  const double a = r[0], b = r[1], c = r[2], d = r[3], e = r[4], f = r[5], g = r[6], h = r[7],
               i = r[8];
  return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
}

Camera MirrorWorldX(const Camera& camera) {
  Camera mirrored = camera;
  for (int r = 0; r < 3; ++r) mirrored.rotation[3 * r] = -camera.rotation[3 * r];
  return mirrored;
}

void MirrorWorldX(PointCloud* points) {
  for (size_t i = 0; i < points->size(); ++i) points->positions[3 * i] *= -1.0f;
}

Status MakeWorldRightHanded(Capture* capture) {
  size_t left = 0, total = 0;
  std::string mixed;
  for (size_t f = 0; f < capture->cameras.size(); ++f) {
    for (size_t c = 0; c < capture->cameras[f].size(); ++c) {
      const bool is_left = RotationDeterminant(capture->cameras[f][c].rotation) < 0;
      left += is_left;
      ++total;
      if (is_left && mixed.size() < 200) {
        mixed += " " + capture->camera_names[c] + "@" + std::to_string(f);
      }
    }
  }
  if (left == 0) return Status::Ok();
  if (left != total) {
    return Status(M4D_ERR_INVALID_ARG,
                  capture->layout + ": " + std::to_string(left) + " of " + std::to_string(total) +
                      " camera poses are left-handed (determinant -1), the rest right-handed; "
                      "no single world frame fits (camera@frame:" +
                      mixed + ")");
  }
  for (std::vector<Camera>& row : capture->cameras) {
    for (Camera& camera : row) camera = MirrorWorldX(camera);
  }
  MirrorWorldX(&capture->initial_points);
  capture->notes.push_back(capture->layout +
                           ": left-handed calibration (rotation determinant -1); the world is "
                           "mirrored to x' = -x, and so is everything written");
  return Status::Ok();
}

}  // namespace m4d
