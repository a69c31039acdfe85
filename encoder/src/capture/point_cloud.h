// PointCloud: coloured points that initialise a keyframe's Gaussians (COLMAP points3D, a
// dataset's own initial cloud, or points sampled from the synthetic scene's meshes).
#ifndef M4D_ENCODER_CAPTURE_POINT_CLOUD_H_
#define M4D_ENCODER_CAPTURE_POINT_CLOUD_H_

#include <cstddef>
#include <vector>

namespace m4d {

struct PointCloud {
  std::vector<float> positions;  // 3 per point, world coordinates
  std::vector<float> colors;     // 3 per point, RGB in [0, 1]

  size_t size() const { return positions.size() / 3; }
};

}  // namespace m4d

#endif  // M4D_ENCODER_CAPTURE_POINT_CLOUD_H_
