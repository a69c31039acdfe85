#include "encoder/src/dataset/colmap_binary.h"

#include <cmath>
#include <string>

#include "encoder/src/image_io/byte_samples.h"
#include "encoder/src/io/little_endian_reader.h"

namespace m4d {
namespace {

// Smallest record of each file, for checking counts against the bytes left.
constexpr size_t kMinCameraBytes = 4 + 4 + 8 + 8;
constexpr size_t kMinImageBytes = 4 + 4 * 8 + 3 * 8 + 4 + 1 + 8;
constexpr size_t kMinPointBytes = 8 + 3 * 8 + 3 + 8 + 8;
constexpr size_t kPoint2dBytes = 8 + 8 + 8;
constexpr size_t kTrackEntryBytes = 4 + 4;
constexpr size_t kMaxNameLength = 4096;

Status Truncated(const char* file) {
  return BitstreamError(std::string("colmap: ") + file + " truncated or malformed");
}

// Reads the leading record count and checks it against the bytes left.
bool ReadCount(LittleEndianReader* reader, size_t min_record_bytes, uint64_t* count) {
  return reader->ReadU64(count) && *count <= reader->remaining() / min_record_bytes;
}

// Values must be finite and within float range, as they end up in floats.
bool ReadDoubles(LittleEndianReader* reader, int n, double* values) {
  for (int i = 0; i < n; ++i) {
    if (!reader->ReadF64(&values[i]) || !(std::fabs(values[i]) <= 1e30)) return false;
  }
  return true;
}

}  // namespace

Status ParseColmapCamerasBinary(const uint8_t* data, size_t size,
                                std::vector<ColmapCamera>* cameras) {
  LittleEndianReader reader(data, size);
  uint64_t count;
  if (!ReadCount(&reader, kMinCameraBytes, &count)) return Truncated("cameras.bin");
  cameras->assign(count, ColmapCamera());
  for (ColmapCamera& camera : *cameras) {
    int32_t model;
    if (!reader.ReadU32(&camera.id) || !reader.ReadI32(&model) || !reader.ReadU64(&camera.width) ||
        !reader.ReadU64(&camera.height)) {
      return Truncated("cameras.bin");
    }
    const int params = ColmapModelParamCount(model);
    if (params < 0) return BitstreamError("colmap: unknown camera model " + std::to_string(model));
    camera.model_id = model;
    camera.params.resize(params);
    if (!ReadDoubles(&reader, params, camera.params.data())) return Truncated("cameras.bin");
  }
  if (reader.remaining() != 0) return Truncated("cameras.bin");
  return Status::Ok();
}

Status ParseColmapImagesBinary(const uint8_t* data, size_t size, std::vector<ColmapImage>* images) {
  LittleEndianReader reader(data, size);
  uint64_t count;
  if (!ReadCount(&reader, kMinImageBytes, &count)) return Truncated("images.bin");
  images->assign(count, ColmapImage());
  for (ColmapImage& image : *images) {
    uint64_t points;
    if (!reader.ReadU32(&image.id) || !ReadDoubles(&reader, 4, image.qvec) ||
        !ReadDoubles(&reader, 3, image.tvec) || !reader.ReadU32(&image.camera_id) ||
        !reader.ReadCString(kMaxNameLength, &image.name) || !reader.ReadU64(&points) ||
        points > reader.remaining() / kPoint2dBytes || !reader.Skip(points * kPoint2dBytes)) {
      return Truncated("images.bin");
    }
  }
  if (reader.remaining() != 0) return Truncated("images.bin");
  return Status::Ok();
}

Status ParseColmapPointsBinary(const uint8_t* data, size_t size, PointCloud* points) {
  LittleEndianReader reader(data, size);
  uint64_t count;
  if (!ReadCount(&reader, kMinPointBytes, &count)) return Truncated("points3D.bin");
  points->positions.resize(3 * count);
  points->colors.resize(3 * count);
  for (uint64_t i = 0; i < count; ++i) {
    uint64_t id, track;
    double xyz[3], error;
    uint8_t rgb[3];
    if (!reader.ReadU64(&id) || !ReadDoubles(&reader, 3, xyz) || !reader.ReadU8(&rgb[0]) ||
        !reader.ReadU8(&rgb[1]) || !reader.ReadU8(&rgb[2]) || !reader.ReadF64(&error) ||
        !reader.ReadU64(&track) || track > reader.remaining() / kTrackEntryBytes ||
        !reader.Skip(track * kTrackEntryBytes)) {
      return Truncated("points3D.bin");
    }
    for (int a = 0; a < 3; ++a) {
      points->positions[3 * i + a] = static_cast<float>(xyz[a]);
      points->colors[3 * i + a] = ByteToFloat(rgb[a]);
    }
  }
  if (reader.remaining() != 0) return Truncated("points3D.bin");
  return Status::Ok();
}

}  // namespace m4d
