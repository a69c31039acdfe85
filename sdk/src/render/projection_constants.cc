#include "sdk/src/render/projection_constants.h"

#include <algorithm>

namespace m4d {

ProjectionConstants MakeProjectionConstants(const Camera& camera) {
  ProjectionConstants pc;
  std::copy(camera.rotation, camera.rotation + 9, pc.rotation);
  std::copy(camera.translation, camera.translation + 3, pc.translation);
  CameraCentre(camera, pc.centre);
  pc.fx = camera.fx;
  pc.fy = camera.fy;
  pc.cx = camera.cx;
  pc.cy = camera.cy;
  pc.near_plane = camera.near_plane;
  const float w = static_cast<float>(camera.width), h = static_cast<float>(camera.height);
  pc.limit_x[0] = (-camera.cx - kFrustumMargin * w) / camera.fx;
  pc.limit_x[1] = (w - camera.cx + kFrustumMargin * w) / camera.fx;
  pc.limit_y[0] = (-camera.cy - kFrustumMargin * h) / camera.fy;
  pc.limit_y[1] = (h - camera.cy + kFrustumMargin * h) / camera.fy;
  pc.width = camera.width;
  pc.height = camera.height;
  pc.tiles_x = (camera.width + kTileSize - 1) / kTileSize;
  pc.tiles_y = (camera.height + kTileSize - 1) / kTileSize;
  return pc;
}

}  // namespace m4d
