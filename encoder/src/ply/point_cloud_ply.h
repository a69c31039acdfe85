// PointCloud import and export as PLY: a "vertex" element with x y z and optional colours
// red green blue, the form COLMAP, nerfstudio and most point-cloud tools exchange.
#ifndef M4D_ENCODER_PLY_POINT_CLOUD_PLY_H_
#define M4D_ENCODER_PLY_POINT_CLOUD_PLY_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "encoder/src/capture/point_cloud.h"
#include "sdk/src/common/status.h"

namespace m4d {

// Any PLY format and property types. Integer colours are scaled by their type's maximum
// (uchar by 255), float colours taken as they are; without colours every point is grey 0.5.
// M4D_ERR_BITSTREAM for missing coordinates, truncated data or non-finite coordinates.
Status DecodePointCloudPly(const uint8_t* data, size_t size, PointCloud* points);
Status ReadPointCloudPly(const std::string& path, PointCloud* points);

// Binary little-endian, x y z float and red green blue uchar.
Status EncodePointCloudPly(const PointCloud& points, std::vector<uint8_t>* bytes);
Status WritePointCloudPly(const std::string& path, const PointCloud& points);

}  // namespace m4d

#endif  // M4D_ENCODER_PLY_POINT_CLOUD_PLY_H_
