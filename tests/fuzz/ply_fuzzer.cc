// libFuzzer target for the PLY readers: the input is a PLY file (or anything else), read as
// a 3DGS Gaussian set and as a point cloud. Reading must fail cleanly or give arrays of the
// promised sizes, never crash, overrun or allocate beyond what the input can hold.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "encoder/src/ply/gaussian_ply.h"
#include "encoder/src/ply/point_cloud_ply.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  m4d::GaussianSet set;
  if (m4d::DecodeGaussianPly(data, size, &set).ok()) {
    const size_t n = set.size();
    if (set.positions.size() != 3 * n || set.rotations.size() != 4 * n ||
        set.sh.size() != static_cast<size_t>(set.sh_floats()) * n) {
      std::abort();
    }
  }
  m4d::PointCloud points;
  if (m4d::DecodePointCloudPly(data, size, &points).ok()) {
    if (points.colors.size() != points.positions.size()) std::abort();
  }
  return 0;
}
