#include "encoder/src/ply/point_cloud_ply.h"

#include <cmath>
#include <cstring>

#include "encoder/src/image_io/byte_samples.h"
#include "encoder/src/image_io/file_bytes.h"
#include "encoder/src/ply/ply_header.h"
#include "encoder/src/ply/ply_reader.h"

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "PLY export assumes a little-endian host");

namespace m4d {
namespace {

// What a stored colour value is divided by to give [0, 1].
float ColourScale(PlyType type) {
  switch (type) {
    case PlyType::kUint8:
      return 255.0f;
    case PlyType::kUint16:
      return 65535.0f;
    case PlyType::kInt8:
      return 127.0f;
    case PlyType::kInt16:
      return 32767.0f;
    case PlyType::kInt32:
      return 2147483647.0f;
    case PlyType::kUint32:
      return 4294967295.0f;
    default:
      return 1.0f;
  }
}

}  // namespace

Status DecodePointCloudPly(const uint8_t* data, size_t size, PointCloud* points) {
  PlyHeader header;
  M4D_RETURN_IF_ERROR(ParsePlyHeader(data, size, &header));
  const int vertex = header.Find("vertex");
  if (vertex < 0) return BitstreamError("ply: no vertex element");
  const PlyElement& element = header.elements[vertex];
  std::vector<std::string> names = {"x", "y", "z"};
  const char* colour_names[3] = {"red", "green", "blue"};
  float scale[3] = {1, 1, 1};
  bool has_colour = true;
  for (int c = 0; c < 3; ++c) {
    const int p = element.Find(colour_names[c]);
    has_colour &= p >= 0 && !element.properties[p].is_list;
    if (p >= 0) scale[c] = ColourScale(element.properties[p].type);
  }
  if (has_colour) names.insert(names.end(), colour_names, colour_names + 3);

  std::vector<float> values;
  size_t rows = 0;
  M4D_RETURN_IF_ERROR(ReadPlyProperties(data, size, header, "vertex", names, &values, &rows));
  points->positions.resize(3 * rows);
  points->colors.assign(3 * rows, 0.5f);
  const size_t stride = names.size();
  for (size_t i = 0; i < rows; ++i) {
    const float* v = &values[i * stride];
    for (int a = 0; a < 3; ++a) {
      if (!std::isfinite(v[a])) return BitstreamError("ply: non-finite point coordinate");
      points->positions[3 * i + a] = v[a];
      if (has_colour) points->colors[3 * i + a] = v[3 + a] / scale[a];
    }
  }
  return Status::Ok();
}

Status ReadPointCloudPly(const std::string& path, PointCloud* points) {
  std::vector<uint8_t> bytes;
  Status status = ReadFileBytes(path, kMaxPlyFileBytes, &bytes);
  if (status.ok()) status = DecodePointCloudPly(bytes.data(), bytes.size(), points);
  if (status.ok()) return status;
  return Status(status.code(), status.message() + " (" + path + ")");
}

Status EncodePointCloudPly(const PointCloud& points, std::vector<uint8_t>* bytes) {
  const size_t n = points.size();
  if (points.positions.size() != 3 * n || points.colors.size() != 3 * n) {
    return Status(M4D_ERR_INVALID_ARG, "ply: point cloud needs 3 positions and 3 colours each");
  }
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(n) +
      "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
      "property uchar green\nproperty uchar blue\nend_header\n";
  constexpr size_t kRowBytes = 3 * sizeof(float) + 3;
  bytes->assign(header.begin(), header.end());
  bytes->resize(header.size() + n * kRowBytes);
  uint8_t* out = bytes->data() + header.size();
  for (size_t i = 0; i < n; ++i, out += kRowBytes) {
    std::memcpy(out, &points.positions[3 * i], 3 * sizeof(float));
    for (int c = 0; c < 3; ++c) out[12 + c] = FloatToByte(points.colors[3 * i + c]);
  }
  return Status::Ok();
}

Status WritePointCloudPly(const std::string& path, const PointCloud& points) {
  std::vector<uint8_t> bytes;
  M4D_RETURN_IF_ERROR(EncodePointCloudPly(points, &bytes));
  return WriteFileBytes(path, bytes);
}

}  // namespace m4d
