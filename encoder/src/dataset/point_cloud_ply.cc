#include "dataset/point_cloud_ply.h"

#include <algorithm>
#include <cstring>
#include <sstream>

#include "image/byte_samples.h"
#include "image/file_bytes.h"

namespace m4d {
namespace {

constexpr size_t kMaxHeaderBytes = 1 << 16;

struct VertexProperty {
  std::string name;
  size_t size = 0;
  size_t offset = 0;
  bool is_float = false;  // float32
  bool is_uchar = false;
};

size_t ScalarSize(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" ||
      type == "float32") {
    return 4;
  }
  if (type == "double" || type == "float64") return 8;
  return 0;
}

struct PlyLayout {
  size_t vertex_count = 0;
  size_t stride = 0;
  std::vector<VertexProperty> properties;
  size_t data_offset = 0;
};

Status ParseHeader(const uint8_t* data, size_t size, PlyLayout* layout) {
  if (size < 4 || std::memcmp(data, "ply\n", 4) != 0) {
    return Status(M4D_ERR_UNSUPPORTED, "ply: not a PLY file");
  }
  const char kEnd[] = "end_header\n";
  const char* text = reinterpret_cast<const char*>(data);
  const size_t limit = std::min(size, kMaxHeaderBytes);
  const void* end = nullptr;
  for (size_t i = 0; i + sizeof(kEnd) - 1 <= limit && end == nullptr; ++i) {
    if (std::memcmp(text + i, kEnd, sizeof(kEnd) - 1) == 0) end = text + i;
  }
  if (end == nullptr) return BitstreamError("ply: no end_header in the first 64 KiB");
  layout->data_offset = static_cast<const char*>(end) - text + sizeof(kEnd) - 1;
  std::istringstream header(std::string(text, layout->data_offset));
  std::string line, element;
  bool format_ok = false, seen_vertex = false;
  while (std::getline(header, line)) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "format") {
      std::string format;
      words >> format;
      if (format != "binary_little_endian") {
        return Status(M4D_ERR_UNSUPPORTED,
                      "ply: format " + format + " (binary_little_endian only)");
      }
      format_ok = true;
    } else if (keyword == "element") {
      long long count = -1;
      words >> element >> count;
      if (!seen_vertex && element != "vertex") {
        return Status(M4D_ERR_UNSUPPORTED, "ply: element " + element + " before the vertices");
      }
      if (element == "vertex") {
        if (seen_vertex || count < 0) return BitstreamError("ply: bad vertex element");
        if (static_cast<unsigned long long>(count) > kMaxPlyPoints) {
          return LimitError("ply: " + std::to_string(count) + " vertices above the limit");
        }
        layout->vertex_count = static_cast<size_t>(count);
        seen_vertex = true;
      }
    } else if (keyword == "property" && element == "vertex") {
      std::string type, name;
      words >> type >> name;
      if (type == "list") return Status(M4D_ERR_UNSUPPORTED, "ply: list property in vertices");
      VertexProperty p;
      p.name = name;
      p.size = ScalarSize(type);
      if (p.size == 0) return BitstreamError("ply: unknown property type " + type);
      p.is_float = type == "float" || type == "float32";
      p.is_uchar = type == "uchar" || type == "uint8";
      p.offset = layout->stride;
      layout->stride += p.size;
      layout->properties.push_back(p);
    }
  }
  if (!format_ok) return BitstreamError("ply: no format line");
  if (!seen_vertex) return BitstreamError("ply: no vertex element");
  return Status::Ok();
}

const VertexProperty* Find(const PlyLayout& layout, const char* name) {
  for (const VertexProperty& p : layout.properties) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

}  // namespace

Status EncodePointCloudPly(const PointCloud& cloud, std::vector<uint8_t>* bytes) {
  const size_t n = cloud.size();
  if (cloud.positions.size() != 3 * n || cloud.colors.size() != 3 * n) {
    return Status(M4D_ERR_INVALID_ARG, "ply: positions and colours differ in count");
  }
  if (n > kMaxPlyPoints) return LimitError("ply: too many points");
  const std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex " +
                             std::to_string(n) +
                             "\nproperty float x\nproperty float y\nproperty float z\n"
                             "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                             "end_header\n";
  bytes->assign(header.begin(), header.end());
  bytes->reserve(header.size() + 15 * n);
  for (size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      uint32_t bits;
      std::memcpy(&bits, &cloud.positions[3 * i + a], 4);
      for (int b = 0; b < 4; ++b) bytes->push_back(static_cast<uint8_t>(bits >> (8 * b)));
    }
    for (int c = 0; c < 3; ++c) bytes->push_back(FloatToByte(cloud.colors[3 * i + c]));
  }
  return Status::Ok();
}

Status WritePointCloudPly(const std::string& path, const PointCloud& cloud) {
  std::vector<uint8_t> bytes;
  M4D_RETURN_IF_ERROR(EncodePointCloudPly(cloud, &bytes));
  return WriteFileBytes(path, bytes);
}

Status DecodePointCloudPly(const uint8_t* data, size_t size, PointCloud* cloud) {
  PlyLayout layout;
  M4D_RETURN_IF_ERROR(ParseHeader(data, size, &layout));
  const VertexProperty* xyz[3] = {Find(layout, "x"), Find(layout, "y"), Find(layout, "z")};
  for (const VertexProperty* p : xyz) {
    if (p == nullptr || !p->is_float) {
      return Status(M4D_ERR_UNSUPPORTED, "ply: vertices need float x, y and z");
    }
  }
  const VertexProperty* rgb[3] = {Find(layout, "red"), Find(layout, "green"), Find(layout, "blue")};
  const bool has_colour =
      rgb[0] && rgb[1] && rgb[2] && rgb[0]->is_uchar && rgb[1]->is_uchar && rgb[2]->is_uchar;
  const size_t available = size - layout.data_offset;
  if (layout.stride == 0 || layout.vertex_count > available / layout.stride) {
    return BitstreamError("ply: file shorter than its " + std::to_string(layout.vertex_count) +
                          " declared vertices");
  }
  const size_t n = layout.vertex_count;
  cloud->positions.resize(3 * n);
  cloud->colors.resize(3 * n);
  const uint8_t* vertex = data + layout.data_offset;
  for (size_t i = 0; i < n; ++i, vertex += layout.stride) {
    for (int a = 0; a < 3; ++a) {
      uint32_t bits = 0;
      for (int b = 0; b < 4; ++b)
        bits |= static_cast<uint32_t>(vertex[xyz[a]->offset + b]) << (8 * b);
      std::memcpy(&cloud->positions[3 * i + a], &bits, 4);
      cloud->colors[3 * i + a] = has_colour ? ByteToFloat(vertex[rgb[a]->offset]) : 0.5f;
    }
  }
  return Status::Ok();
}

Status ReadPointCloudPly(const std::string& path, PointCloud* cloud) {
  std::vector<uint8_t> bytes;
  M4D_RETURN_IF_ERROR(ReadFileBytes(path, kMaxHeaderBytes + kMaxPlyPoints * 64, &bytes));
  Status status = DecodePointCloudPly(bytes.data(), bytes.size(), cloud);
  if (!status.ok()) return Status(status.code(), status.message() + ": " + path);
  return status;
}

}  // namespace m4d
