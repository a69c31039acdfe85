#include "encoder/src/ply/ply_reader.h"

#include <cmath>
#include <cstdlib>
#include <cstring>

namespace m4d {
namespace {

// Longest ASCII number accepted; longer tokens are malformed.
constexpr size_t kMaxTokenLength = 64;

// Walks the data section value by value.
class PlyCursor {
 public:
  PlyCursor(const uint8_t* data, size_t size, size_t offset, PlyFormat format)
      : data_(data), size_(size), pos_(offset), format_(format) {}

  size_t remaining() const { return size_ - pos_; }
  bool ascii() const { return format_ == PlyFormat::kAscii; }

  bool Read(PlyType type, double* value) {
    return ascii() ? ReadToken(value) : ReadBinary(type, value);
  }

  // Skips n values of the type.
  bool Skip(PlyType type, uint64_t n) {
    if (!ascii()) {
      const uint64_t bytes = static_cast<uint64_t>(PlyTypeSize(type));
      if (n > remaining() / bytes) return false;
      pos_ += n * bytes;
      return true;
    }
    double ignored;
    for (uint64_t i = 0; i < n; ++i) {
      if (!ReadToken(&ignored)) return false;
    }
    return true;
  }

  // A list's length: a non-negative integer no larger than the values left could hold.
  bool ReadListLength(PlyType type, uint64_t* n) {
    double value;
    if (!Read(type, &value) || !(value >= 0) || value != std::floor(value) ||
        value > static_cast<double>(remaining())) {
      return false;
    }
    *n = static_cast<uint64_t>(value);
    return true;
  }

 private:
  bool ReadBinary(PlyType type, double* value) {
    const int bytes = PlyTypeSize(type);
    if (remaining() < static_cast<size_t>(bytes)) return false;
    uint64_t bits = 0;
    for (int i = 0; i < bytes; ++i) {
      const int shift = format_ == PlyFormat::kBinaryLittleEndian ? i : bytes - 1 - i;
      bits |= static_cast<uint64_t>(data_[pos_ + i]) << (8 * shift);
    }
    pos_ += bytes;
    *value = Convert(type, bits);
    return true;
  }

  static double Convert(PlyType type, uint64_t bits) {
    switch (type) {
      case PlyType::kInt8:
        return static_cast<int8_t>(bits);
      case PlyType::kUint8:
        return static_cast<uint8_t>(bits);
      case PlyType::kInt16:
        return static_cast<int16_t>(bits);
      case PlyType::kUint16:
        return static_cast<uint16_t>(bits);
      case PlyType::kInt32:
        return static_cast<int32_t>(bits);
      case PlyType::kUint32:
        return static_cast<uint32_t>(bits);
      case PlyType::kFloat32: {
        const uint32_t b = static_cast<uint32_t>(bits);
        float f;
        std::memcpy(&f, &b, 4);
        return f;
      }
      case PlyType::kFloat64: {
        double d;
        std::memcpy(&d, &bits, 8);
        return d;
      }
    }
    return 0;
  }

  static bool IsSpace(uint8_t c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

  bool ReadToken(double* value) {
    while (pos_ < size_ && IsSpace(data_[pos_])) ++pos_;
    const size_t start = pos_;
    while (pos_ < size_ && !IsSpace(data_[pos_]) && pos_ - start <= kMaxTokenLength) ++pos_;
    const size_t length = pos_ - start;
    if (length == 0 || length > kMaxTokenLength) return false;
    char token[kMaxTokenLength + 1];
    std::memcpy(token, data_ + start, length);
    token[length] = '\0';
    char* end = nullptr;
    *value = std::strtod(token, &end);
    return end == token + length;
  }

  const uint8_t* data_;
  size_t size_;
  size_t pos_;
  PlyFormat format_;
};

bool SkipRow(const PlyElement& element, PlyCursor* cursor) {
  for (const PlyProperty& property : element.properties) {
    uint64_t n = 1;
    if (property.is_list && !cursor->ReadListLength(property.count_type, &n)) return false;
    if (!cursor->Skip(property.type, n)) return false;
  }
  return true;
}

// Bytes (binary) or characters (ASCII, a digit and a separator per value) a row takes at
// least, so that a declared count can be checked against the data left.
uint64_t MinimumRowBytes(const PlyElement& element, PlyFormat format) {
  uint64_t bytes = 0;
  for (const PlyProperty& property : element.properties) {
    if (format == PlyFormat::kAscii) {
      bytes += 2;
    } else {
      bytes += PlyTypeSize(property.is_list ? property.count_type : property.type);
    }
  }
  return bytes;
}

// Doubles beyond the float range become infinities (a plain cast would be undefined).
float ToFloat(double value) {
  constexpr double kMax = 3.4028234663852886e38;
  if (value > kMax) return HUGE_VALF;
  if (value < -kMax) return -HUGE_VALF;
  return static_cast<float>(value);
}

Status Truncated(const PlyElement& element) {
  return BitstreamError("ply: data of element '" + element.name + "' truncated or malformed");
}

Status SkipElement(const PlyElement& element, PlyCursor* cursor) {
  bool fixed_size = !cursor->ascii();
  for (const PlyProperty& property : element.properties) fixed_size &= !property.is_list;
  if (fixed_size) {
    const uint64_t row = MinimumRowBytes(element, PlyFormat::kBinaryLittleEndian);
    if (row != 0 && element.count > cursor->remaining() / row) return Truncated(element);
    return cursor->Skip(PlyType::kUint8, row * element.count) ? Status::Ok() : Truncated(element);
  }
  for (uint64_t row = 0; row < element.count; ++row) {
    if (!SkipRow(element, cursor)) return Truncated(element);
  }
  return Status::Ok();
}

}  // namespace

Status ReadPlyProperties(const uint8_t* data, size_t size, const PlyHeader& header,
                         const std::string& element_name, const std::vector<std::string>& names,
                         std::vector<float>* values, size_t* rows) {
  const int target = header.Find(element_name);
  if (target < 0) return BitstreamError("ply: no element '" + element_name + "'");
  const PlyElement& element = header.elements[target];
  // For each property of the element, the output column it goes to, or -1.
  std::vector<int> column(element.properties.size(), -1);
  for (size_t i = 0; i < names.size(); ++i) {
    const int p = element.Find(names[i]);
    if (p < 0 || element.properties[p].is_list) {
      return BitstreamError("ply: element '" + element_name + "' has no scalar property '" +
                            names[i] + "'");
    }
    column[p] = static_cast<int>(i);
  }
  if (header.data_offset > size) return BitstreamError("ply: header offset beyond the data");
  PlyCursor cursor(data, size, header.data_offset, header.format);
  for (int e = 0; e < target; ++e) M4D_RETURN_IF_ERROR(SkipElement(header.elements[e], &cursor));

  const uint64_t row_bytes = MinimumRowBytes(element, header.format);
  // A row needs at least row_bytes, except that the last ASCII value needs no separator.
  const uint64_t available = cursor.remaining() + (cursor.ascii() ? 1 : 0);
  if (row_bytes != 0 && element.count > available / row_bytes) return Truncated(element);
  if (element.count > SIZE_MAX / (names.empty() ? 1 : names.size())) return Truncated(element);
  *rows = static_cast<size_t>(element.count);
  values->assign(*rows * names.size(), 0.0f);
  float* out = values->data();
  for (size_t row = 0; row < *rows; ++row, out += names.size()) {
    for (size_t p = 0; p < element.properties.size(); ++p) {
      const PlyProperty& property = element.properties[p];
      if (property.is_list) {
        uint64_t n = 0;
        if (!cursor.ReadListLength(property.count_type, &n) || !cursor.Skip(property.type, n)) {
          return Truncated(element);
        }
        continue;
      }
      double value;
      if (!cursor.Read(property.type, &value)) return Truncated(element);
      if (column[p] >= 0) out[column[p]] = ToFloat(value);
    }
  }
  return Status::Ok();
}

}  // namespace m4d
