// LittleEndianReader: bounds-checked reads of little-endian scalars from a byte span, for
// the binary file formats datasets come in (PLY, COLMAP, npy, zip). Every read reports
// failure instead of reading past the end.
#ifndef M4D_ENCODER_IO_LITTLE_ENDIAN_READER_H_
#define M4D_ENCODER_IO_LITTLE_ENDIAN_READER_H_

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

namespace m4d {

template <size_t N>
struct UnsignedOfSizeImpl;
template <>
struct UnsignedOfSizeImpl<1> {
  using type = uint8_t;
};
template <>
struct UnsignedOfSizeImpl<2> {
  using type = uint16_t;
};
template <>
struct UnsignedOfSizeImpl<4> {
  using type = uint32_t;
};
template <>
struct UnsignedOfSizeImpl<8> {
  using type = uint64_t;
};
template <size_t N>
using UnsignedOfSize = typename UnsignedOfSizeImpl<N>::type;

class LittleEndianReader {
 public:
  LittleEndianReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}

  size_t remaining() const { return size_ - pos_; }
  size_t position() const { return pos_; }
  const uint8_t* cursor() const { return data_ + pos_; }

  bool Skip(size_t n) {
    if (remaining() < n) return false;
    pos_ += n;
    return true;
  }
  bool ReadBytes(size_t n, const uint8_t** out) {
    if (remaining() < n) return false;
    *out = data_ + pos_;
    pos_ += n;
    return true;
  }
  bool ReadU8(uint8_t* v) { return ReadRaw(v); }
  bool ReadU16(uint16_t* v) { return ReadRaw(v); }
  bool ReadU32(uint32_t* v) { return ReadRaw(v); }
  bool ReadU64(uint64_t* v) { return ReadRaw(v); }
  bool ReadI32(int32_t* v) { return ReadRaw(v); }
  bool ReadI64(int64_t* v) { return ReadRaw(v); }
  bool ReadF32(float* v) { return ReadRaw(v); }
  bool ReadF64(double* v) { return ReadRaw(v); }
  // A NUL-terminated string of at most max_length bytes (the NUL is consumed).
  bool ReadCString(size_t max_length, std::string* s) {
    const size_t limit = remaining() < max_length + 1 ? remaining() : max_length + 1;
    const void* nul = std::memchr(data_ + pos_, 0, limit);
    if (!nul) return false;
    const size_t length = static_cast<const uint8_t*>(nul) - (data_ + pos_);
    s->assign(reinterpret_cast<const char*>(data_ + pos_), length);
    pos_ += length + 1;
    return true;
  }

 private:
  // Byte-wise assembly, so the result does not depend on the host's byte order.
  template <typename T>
  bool ReadRaw(T* v) {
    if (remaining() < sizeof(T)) return false;
    uint64_t bits = 0;
    for (size_t i = 0; i < sizeof(T); ++i) {
      bits |= static_cast<uint64_t>(data_[pos_ + i]) << (8 * i);
    }
    const UnsignedOfSize<sizeof(T)> sized = static_cast<UnsignedOfSize<sizeof(T)>>(bits);
    std::memcpy(v, &sized, sizeof(T));
    pos_ += sizeof(T);
    return true;
  }

  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
};

}  // namespace m4d

#endif  // M4D_ENCODER_IO_LITTLE_ENDIAN_READER_H_
