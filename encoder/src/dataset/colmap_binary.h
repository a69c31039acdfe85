// Parsers for COLMAP's binary model files (cameras.bin, images.bin, points3D.bin). Counts
// are checked against the bytes left before anything is allocated.
#ifndef M4D_ENCODER_DATASET_COLMAP_BINARY_H_
#define M4D_ENCODER_DATASET_COLMAP_BINARY_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "encoder/src/dataset/colmap_model.h"
#include "sdk/src/common/status.h"

namespace m4d {

// M4D_ERR_BITSTREAM for truncated data, trailing bytes or unknown camera models.
Status ParseColmapCamerasBinary(const uint8_t* data, size_t size,
                                std::vector<ColmapCamera>* cameras);
Status ParseColmapImagesBinary(const uint8_t* data, size_t size, std::vector<ColmapImage>* images);
Status ParseColmapPointsBinary(const uint8_t* data, size_t size, PointCloud* points);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_COLMAP_BINARY_H_
