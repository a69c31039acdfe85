#include "synthetic_scene/world_mirror.h"

namespace m4d {

Camera MirrorWorldX(const Camera& camera) {
  Camera mirrored = camera;
  for (int row = 0; row < 3; ++row) mirrored.rotation[3 * row] = -camera.rotation[3 * row];
  return mirrored;
}

void MirrorWorldX(PointCloud* points) {
  for (size_t i = 0; i < points->size(); ++i) points->positions[3 * i] = -points->positions[3 * i];
}

}  // namespace m4d
