// ByteReader: bounds-checked little-endian reads from a byte span. Every read reports
// failure instead of reading past the end, so parsers can never overrun a payload.
#ifndef M4D_SDK_COMMON_BYTE_READER_H_
#define M4D_SDK_COMMON_BYTE_READER_H_

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace m4d {

class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}

  size_t remaining() const { return size_ - pos_; }
  size_t position() const { return pos_; }
  const uint8_t* cursor() const { return data_ + pos_; }

  bool ReadU8(uint8_t* v) {
    if (remaining() < 1) return false;
    *v = data_[pos_++];
    return true;
  }
  bool ReadU16(uint16_t* v) {
    if (remaining() < 2) return false;
    *v = static_cast<uint16_t>(data_[pos_] | (data_[pos_ + 1] << 8));
    pos_ += 2;
    return true;
  }
  bool ReadU32(uint32_t* v) {
    if (remaining() < 4) return false;
    *v = LoadU32(data_ + pos_);
    pos_ += 4;
    return true;
  }
  // Reads an f32 and rejects NaN and infinities (every transmitted f32 is finite).
  bool ReadFiniteF32(float* v) {
    uint32_t bits;
    if (!ReadU32(&bits)) return false;
    std::memcpy(v, &bits, 4);
    return std::isfinite(*v);
  }
  // LEB128, at most 5 bytes, value below 2^32.
  bool ReadVarUint(uint32_t* v) {
    uint64_t value = 0;
    for (int i = 0; i < 5; ++i) {
      uint8_t byte;
      if (!ReadU8(&byte)) return false;
      value |= static_cast<uint64_t>(byte & 0x7f) << (7 * i);
      if (!(byte & 0x80)) {
        if (value > 0xffffffffu) return false;
        *v = static_cast<uint32_t>(value);
        return true;
      }
    }
    return false;
  }
  bool ReadVarSint(int32_t* v) {
    uint32_t z;
    if (!ReadVarUint(&z)) return false;
    *v = static_cast<int32_t>((z >> 1) ^ (0u - (z & 1u)));
    return true;
  }
  // Returns a pointer to the next `n` bytes and advances past them.
  bool ReadBytes(size_t n, const uint8_t** out) {
    if (remaining() < n) return false;
    *out = data_ + pos_;
    pos_ += n;
    return true;
  }

  static uint32_t LoadU32(const uint8_t* p) {
    return static_cast<uint32_t>(p[0]) | (static_cast<uint32_t>(p[1]) << 8) |
           (static_cast<uint32_t>(p[2]) << 16) | (static_cast<uint32_t>(p[3]) << 24);
  }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
};

}  // namespace m4d

#endif  // M4D_SDK_COMMON_BYTE_READER_H_
