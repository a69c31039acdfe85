// PLY headers: the elements and properties a PLY file declares, parsed with limits, and the
// size of their data, so readers can check declared counts against the file before
// allocating anything.
#ifndef M4D_ENCODER_PLY_PLY_HEADER_H_
#define M4D_ENCODER_PLY_PLY_HEADER_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sdk/src/common/status.h"

namespace m4d {

// Largest PLY file read (whole, into memory): 4 GiB, e.g. 16 million 3DGS Gaussians.
constexpr size_t kMaxPlyFileBytes = size_t{1} << 32;

enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

enum class PlyType { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

int PlyTypeSize(PlyType type);
// The name a header uses for the type ("float", "uchar", ...).
const char* PlyTypeName(PlyType type);

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat32;  // of the values (list items for a list)
  bool is_list = false;
  PlyType count_type = PlyType::kUint8;  // of a list's length
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;

  // Index of the named property, or -1.
  int Find(const std::string& property) const;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::kBinaryLittleEndian;
  std::vector<PlyElement> elements;
  size_t data_offset = 0;  // first byte after "end_header\n"

  // Index of the named element, or -1.
  int Find(const std::string& element) const;
};

// Parses the header at the start of data. M4D_ERR_UNSUPPORTED without the "ply" magic or
// for an unknown format version, M4D_ERR_BITSTREAM for a malformed header, M4D_ERR_LIMIT
// for a header beyond 1 MiB, 256 elements or 4096 properties per element.
Status ParsePlyHeader(const uint8_t* data, size_t size, PlyHeader* header);

}  // namespace m4d

#endif  // M4D_ENCODER_PLY_PLY_HEADER_H_
