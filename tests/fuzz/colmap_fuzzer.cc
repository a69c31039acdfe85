// libFuzzer target for COLMAP's binary model files: the first byte picks cameras.bin,
// images.bin or points3D.bin, the rest is the file. Parsing must fail cleanly or give
// records that match their declared sizes; cameras are converted to intrinsics and lens distortion.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "encoder/src/dataset/colmap_binary.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const uint8_t which = data[0] % 3;
  ++data;
  --size;
  if (which == 0) {
    std::vector<m4d::ColmapCamera> cameras;
    if (!m4d::ParseColmapCamerasBinary(data, size, &cameras).ok()) return 0;
    for (const m4d::ColmapCamera& camera : cameras) {
      if (static_cast<int>(camera.params.size()) != m4d::ColmapModelParamCount(camera.model_id)) {
        std::abort();
      }
      double fx, fy, cx, cy;
      m4d::LensDistortion distortion;
      (void)m4d::ColmapIntrinsics(camera, &fx, &fy, &cx, &cy, &distortion);
    }
  } else if (which == 1) {
    std::vector<m4d::ColmapImage> images;
    (void)m4d::ParseColmapImagesBinary(data, size, &images);
  } else {
    m4d::PointCloud points;
    if (m4d::ParseColmapPointsBinary(data, size, &points).ok() &&
        points.colors.size() != points.positions.size()) {
      std::abort();
    }
  }
  return 0;
}
