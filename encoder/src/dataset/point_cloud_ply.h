// Point clouds as binary PLY files: x y z (float) and red green blue (uchar), the form of
// nerfstudio's and 3DGS's initial point clouds.
//
// Reading takes binary little-endian files with a "vertex" element holding float x, y, z
// and, optionally, uchar red, green, blue (grey 0.5 without them); other scalar properties
// are skipped, and elements after the vertices are ignored. ASCII and big-endian files and
// list properties in the vertex element give M4D_ERR_UNSUPPORTED; a malformed header or
// fewer bytes than the header declares give M4D_ERR_BITSTREAM (checked before allocating).
#ifndef M4D_ENCODER_DATASET_POINT_CLOUD_PLY_H_
#define M4D_ENCODER_DATASET_POINT_CLOUD_PLY_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "common/status.h"
#include "dataset/point_cloud.h"

namespace m4d {

// Largest point cloud read or written: 2^26 points.
constexpr size_t kMaxPlyPoints = size_t{1} << 26;

// Colours are stored as FloatToByte(c).
Status WritePointCloudPly(const std::string& path, const PointCloud& cloud);
Status EncodePointCloudPly(const PointCloud& cloud, std::vector<uint8_t>* bytes);

Status ReadPointCloudPly(const std::string& path, PointCloud* cloud);
Status DecodePointCloudPly(const uint8_t* data, size_t size, PointCloud* cloud);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_POINT_CLOUD_PLY_H_
