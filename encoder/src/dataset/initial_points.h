// Loading an initial point cloud from wherever a user keeps one: a COLMAP sparse model
// directory (its points3D) or a PLY file.
#ifndef M4D_ENCODER_DATASET_INITIAL_POINTS_H_
#define M4D_ENCODER_DATASET_INITIAL_POINTS_H_

#include <string>

#include "encoder/src/capture/point_cloud.h"
#include "sdk/src/common/status.h"

namespace m4d {

// A directory is read as a COLMAP model (points3D.bin or points3D.txt), anything else as a
// PLY point cloud (see point_cloud_ply.h).
Status LoadInitialPoints(const std::string& path, PointCloud* points);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_INITIAL_POINTS_H_
