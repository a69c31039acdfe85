#include "encoder/src/dataset/initial_points.h"

#include <filesystem>
#include <system_error>

#include "encoder/src/dataset/colmap_model.h"
#include "encoder/src/ply/point_cloud_ply.h"

namespace m4d {

Status LoadInitialPoints(const std::string& path, PointCloud* points) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) return ReadColmapPoints(path, points);
  return ReadPointCloudPly(path, points);
}

}  // namespace m4d
