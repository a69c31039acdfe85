#include "encoder/src/train/scene_extent.h"

#include <algorithm>
#include <cmath>

namespace m4d {

SceneBounds CameraSceneBounds(const std::vector<Camera>& cameras) {
  SceneBounds bounds;
  if (cameras.empty()) return bounds;
  std::vector<float> centres(3 * cameras.size());
  double sum[3] = {0, 0, 0};
  for (size_t c = 0; c < cameras.size(); ++c) {
    CameraCentre(cameras[c], &centres[3 * c]);
    for (int a = 0; a < 3; ++a) sum[a] += centres[3 * c + a];
  }
  for (int a = 0; a < 3; ++a) bounds.centre[a] = static_cast<float>(sum[a] / cameras.size());
  double largest = 0;
  for (size_t c = 0; c < cameras.size(); ++c) {
    double d2 = 0;
    for (int a = 0; a < 3; ++a) {
      const double d = centres[3 * c + a] - bounds.centre[a];
      d2 += d * d;
    }
    largest = std::max(largest, std::sqrt(d2));
  }
  bounds.extent = static_cast<float>(1.1 * largest);
  return bounds;
}

}  // namespace m4d
